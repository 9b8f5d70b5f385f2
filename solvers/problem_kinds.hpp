// The check each backend entry makes before any work: InputError when it does not solve the
// QP's kind of problem (frictionless, Tresca, Coulomb).
#pragma once

#include "contactqp/qp.hpp"

namespace contactqp::detail {

void require_supported(Backend backend, const QuadraticProgram& qp);

}  // namespace contactqp::detail
