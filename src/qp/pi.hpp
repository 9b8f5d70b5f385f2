// π, defined once: every file that needs it includes this instead of a constant of its own (a
// unity build compiles several files as one, where two definitions would collide).
#pragma once

namespace contactqp {

inline constexpr double kPi = 3.14159265358979323846;

}  // namespace contactqp
