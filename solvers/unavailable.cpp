// Entry points of the backends whose library was not found at configure time (Ipopt and NLopt
// are optional). backend_available() reports them false, so validate_options() refuses them
// before any of these can be reached; they exist so that the registry links either way.
#include "backends.hpp"
#include "contactqp/errors.hpp"

namespace contactqp::detail {
#if !defined(CONTACTQP_HAVE_IPOPT) || !defined(CONTACTQP_HAVE_NLOPT)
namespace {

[[noreturn]] void not_built(Backend backend) {
  throw InputError("backend", "= " + to_string(backend) + ": was not built into this copy of contactqp");
}

}  // namespace
#endif

#ifndef CONTACTQP_HAVE_IPOPT
void check_ipopt_options(const SolveOptions&) { not_built(Backend::Ipopt); }
SolveResult solve_ipopt(const QuadraticProgram&, const SolveOptions&) { not_built(Backend::Ipopt); }
#endif

#ifndef CONTACTQP_HAVE_NLOPT
void check_nlopt_options(const SolveOptions&) { not_built(Backend::Nlopt); }
SolveResult solve_nlopt(const QuadraticProgram&, const SolveOptions&) { not_built(Backend::Nlopt); }
#endif

}  // namespace contactqp::detail
