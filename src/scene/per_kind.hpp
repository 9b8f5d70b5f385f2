// PerKind{[](PlaneObstacle&) {...}, [](CircleObstacle&) {...}, ...}: one call operator per kind
// of a std::variant, for std::visit. Written this way a visitor names every kind, and a kind
// added to the variant fails to compile where it is not handled — no catch-all branch that
// quietly treats the new kind as one of the old (an obstacle "with a center").
#pragma once

namespace contactqp::detail {

template <class... Kinds>
struct PerKind : Kinds... {
  using Kinds::operator()...;
};
template <class... Kinds>
PerKind(Kinds...) -> PerKind<Kinds...>;

}  // namespace contactqp::detail
