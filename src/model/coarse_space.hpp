// The P1 level of a quadratic mesh (contactqp/coarse_space.hpp) built from the model.
#pragma once

#include "contactqp/coarse_space.hpp"
#include "contactqp/model.hpp"

namespace contactqp::detail {

// Empty for linear elements. Columns that reach no free DOF (a vertex whose element patch is
// all prescribed) are left out: they would make PᵀKP singular.
CoarseSpace p1_coarse_space(const Model& model);

}  // namespace contactqp::detail
