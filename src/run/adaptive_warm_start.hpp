// The start of an adaptive run's next solve (docs/adaptive.md): the last cycle's answer carried
// to the next mesh.
#pragma once

#include <memory>
#include <vector>

#include "contactqp/model.hpp"
#include "contactqp/qp.hpp"
#include "mesh/point_locator.hpp"

namespace contactqp::detail {

class WarmStart {
 public:
  // The last cycle's model, QP and converged answer: its displacement and contact pressure at
  // the vertices of each body's mesh.
  WarmStart(const Model& model, const QuadraticProgram& qp, const SolveResult& result);

  // SolveOptions::initial on a new mesh of the same scene: u at each free DOF the last
  // displacement interpolated at the node (each body's from its own last mesh; a rigid
  // surface's DOF as it was), λ at each row the last contact pressure interpolated at its node
  // times the row's tributary. u is left empty when either model rotates DOF frames.
  InitialGuess operator()(const Model& model, const QuadraticProgram& qp) const;

 private:
  struct Body {
    std::shared_ptr<const PointLocator> locator;
    std::vector<std::vector<double>> displacement;  // per component, per vertex (global axes)
    std::vector<double> pressure;                   // per vertex; 0 off the contact
  };
  int dim_ = 2;
  bool global_frames_ = true;
  std::vector<Body> bodies_;
  std::vector<double> rigid_surface_values_;  // the rigid surfaces' DOFs, then their angles, in model order
};

}  // namespace contactqp::detail
