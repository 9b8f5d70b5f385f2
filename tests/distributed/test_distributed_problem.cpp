// The distributed bound QP (src/distributed/distributed_problem.hpp), every rank of mpirun
// -n 1, 2, 4 together: its rows are the nodes' dim DOFs (block size dim), a prescribed DOF's row
// holds only its diagonal, the rigid modes are orthonormal and vanish there, and the P2 → P1
// interpolation reproduces a linear field exactly (the vertex values of u = M x give M x at every
// free DOF, in the bound form's variables; x of a mid-edge node the middle of its edge). And the
// loop's solver of A after the solve: the certificate's θ = bᵀA⁻¹b by its energy rule, against the
// same product from a solve to the round-off.
#include <mpi.h>

#include <catch2/catch.hpp>

#include "contactqp/processes.hpp"
#include "contactqp/scene.hpp"
#include "distributed/distributed_pdas.hpp"
#include "distributed/distributed_problem.hpp"
#include "test_support.hpp"

using namespace contactqp;
using contactqp::testing::source_path;

namespace {

Scene small_scene(const std::string& path) {
  Scene scene = load_scene(source_path(path));
  scene.body.mesh.refinements = 1;
  scene.body.mesh.contact_size *= 4;
  scene.body.mesh.size *= 2;
  scene.body.mesh.order = 2;
  return scene;
}

// The largest |x| over every rank.
double largest(double x) {
  MPI_Allreduce(MPI_IN_PLACE, &x, 1, MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD);
  return x;
}

void check_problem(const Scene& scene) {
  start_process_runtime();
  const detail::DistributedModel model = detail::build_distributed_model(scene, BuildOptions());
  const detail::DistributedBoundQp qp = detail::assemble_distributed_bound_qp(model);
  const Model& local = model.local;
  const int dim = local.dim;
  PetscInt block = 0;
  MatGetBlockSize(qp.A, &block);
  CHECK(block == dim);

  // A prescribed DOF's row: its diagonal alone, positive.
  int bad_rows = 0;
  for (int node = 0; node < model.n_owned; ++node)
    for (int c = 0; c < dim && model.node_row[node] >= 0; ++c) {
      if (local.free_index[dim * node + c] >= 0) continue;
      const PetscInt row = model.node_row[node] + c;
      PetscInt n = 0;
      const PetscInt* columns = nullptr;
      const PetscScalar* values = nullptr;
      MatGetRow(qp.A, row, &n, &columns, &values);
      bad_rows += !(n == 1 && columns[0] == row && values[0] > 0);
      MatRestoreRow(qp.A, row, &n, &columns, &values);
    }
  CHECK(largest(bad_rows) == 0);

  // The modes: orthonormal.
  const int k = static_cast<int>(qp.near_null_space.size());
  REQUIRE(k == (dim == 2 ? 3 : 6));
  double worst = 0;
  for (int i = 0; i < k; ++i)
    for (int j = 0; j < k; ++j) {
      PetscScalar dot = 0;
      VecDot(qp.near_null_space[i], qp.near_null_space[j], &dot);
      worst = std::max(worst, std::abs(dot - (i == j ? 1.0 : 0.0)));
    }
  CHECK(worst < 1e-12);

  // P (v-variables) times the vertex values of u = M x (a candidate vertex's in its variables,
  // T (M x)): T (M x) at the free DOFs, 0 at the prescribed ones.
  REQUIRE(qp.coarse_interpolation);
  Eigen::Matrix3d M;
  M << 0.3, -1.1, 0.7, 2.0, 0.4, -0.5, -0.2, 0.9, 1.3;
  Vec coarse = nullptr, fine = nullptr;
  MatCreateVecs(qp.coarse_interpolation, &coarse, &fine);
  // The vertices' values (P's columns dim·vertex + c, an own vertex's on this rank).
  PetscInt first_column = 0, end_column = 0;
  MatGetOwnershipRangeColumn(qp.coarse_interpolation, &first_column, &end_column);
  PetscScalar* c = nullptr;
  VecGetArray(coarse, &c);
  for (int node = 0; node < model.n_owned; ++node) {
    if (qp.vertex_of_node[node] < 0) continue;
    Eigen::Vector3d value = M * local.mesh.nodes[node];
    // A candidate vertex's columns are its own variables: T times its group's components.
    const int t = qp.transform_of_node[node];
    if (t >= 0) {
      const detail::NodeTransform& transform = qp.transforms[t];
      std::vector<int> component;
      for (int column : transform.columns)
        for (int d = 0; d < dim; ++d)
          if (local.free_index[dim * node + d] == column) component.push_back(d);
      Eigen::VectorXd group(component.size());
      for (std::size_t a = 0; a < component.size(); ++a) group[a] = value[component[a]];
      group = transform.T * group;
      for (std::size_t a = 0; a < component.size(); ++a) value[component[a]] = group[a];
    }
    for (int d = 0; d < dim; ++d) c[dim * qp.vertex_of_node[node] + d - first_column] = value[d];
  }
  VecRestoreArray(coarse, &c);
  MatMult(qp.coarse_interpolation, coarse, fine);
  const PetscScalar* y = nullptr;
  VecGetArrayRead(fine, &y);
  double error = 0, scale = 0;
  // A linear field at a mid-edge node is the mean of its edge's ends (the node itself may sit
  // on the curved boundary, off the chord).
  std::vector<Eigen::Vector3d> position = local.mesh.nodes;
  const int nv = dim + 1, npe = local.mesh.nodes_per_element();
  const int edges[6][2] = {{0, 1}, {1, 2}, {2, 0}, {0, 3}, {1, 3}, {2, 3}};
  for (int e = 0; e < local.mesh.n_elements(); ++e) {
    const int* v = local.mesh.element(e);
    for (int k = nv; k < npe; ++k)
      position[v[k]] = 0.5 * (local.mesh.nodes[v[edges[k - nv][0]]] + local.mesh.nodes[v[edges[k - nv][1]]]);
  }
  for (int node = 0; node < model.n_owned; ++node) {
    if (model.node_row[node] < 0) continue;
    Eigen::VectorXd expected = (M * position[node]).head(dim);
    const int t = qp.transform_of_node[node];
    for (int comp = 0; comp < dim; ++comp) {
      const int free = local.free_index[dim * node + comp];
      double want = free >= 0 ? expected[comp] : 0.0;
      if (t >= 0 && free >= 0) {
        const detail::NodeTransform& transform = qp.transforms[t];
        want = 0;
        for (std::size_t a = 0; a < transform.columns.size(); ++a)
          if (transform.columns[a] == free)
            for (std::size_t b = 0; b < transform.columns.size(); ++b)
              for (int d = 0; d < dim; ++d)
                if (local.free_index[dim * node + d] == transform.columns[b]) want += transform.T(a, b) * expected[d];
        // A free component outside the group keeps its u.
        bool in_group = false;
        for (int column : transform.columns) in_group = in_group || column == free;
        if (!in_group) want = expected[comp];
      }
      error = std::max(error, std::abs(y[model.node_row[node] + comp - model.first_row] - want));
      scale = std::max(scale, std::abs(want));
    }
  }
  VecRestoreArrayRead(fine, &y);
  VecDestroy(&coarse);
  VecDestroy(&fine);
  CHECK(largest(error) <= 1e-12 * largest(scale));
}

}  // namespace

TEST_CASE("the distributed sphere's bound QP: block rows, prescribed rows, modes, P2 to P1", "[distributed]") {
  check_problem(small_scene("scenes/hertz-sphere.json"));
}

TEST_CASE("the distributed half disc's bound QP: block rows, prescribed rows, modes, P2 to P1", "[distributed]") {
  check_problem(small_scene("scenes/hertz.json"));
}

// The loop without bounds (--no-contact: one linear solve), then θ = bᵀA⁻¹b twice with its kept
// solver of A: once at the inner rule (relative residual 1e-13 here: θ to the round-off), once by
// the energy rule at 1e-6 θ, which must land within that of the first from below (CG's bᵀx_k
// grows to θ) and take fewer iterations.
TEST_CASE("the kept hierarchy's energy solve gives theta to its tolerance, from below, in fewer iterations",
          "[distributed]") {
  start_process_runtime();
  const detail::DistributedModel model =
      detail::build_distributed_model(small_scene("scenes/hertz-sphere.json"), BuildOptions());
  const detail::DistributedBoundQp qp = detail::assemble_distributed_bound_qp(model);
  detail::DistributedPdasOptions options;
  options.tol = 1e-10;
  options.without_bounds = true;
  detail::DistributedPdasResult solved = detail::solve_distributed_pdas(qp, options);
  REQUIRE(solved.status == Status::Converged);
  CHECK(solved.iterations == 1);
  CHECK(solved.active == 0);
  CHECK(solved.mu.size() == qp.bounded.size());
  REQUIRE(solved.solver_of_A);

  Vec x = nullptr;
  VecDuplicate(qp.b, &x);
  PetscReal force = 0;
  VecNorm(qp.b, NORM_INFINITY, &force);
  REQUIRE(force > 0);
  long long before = solved.solver_of_A->iterations();
  REQUIRE(solved.solver_of_A->solve(qp.b, x, force));
  const long long exact_iterations = solved.solver_of_A->iterations() - before;
  PetscScalar exact = 0;
  VecDot(qp.b, x, &exact);
  REQUIRE(exact > 0);

  before = solved.solver_of_A->iterations();
  PetscScalar theta = 0;
  REQUIRE(solved.solver_of_A->energy(qp.b, x, force, 1e-6 * exact, &theta));
  const long long energy_iterations = solved.solver_of_A->iterations() - before;
  CHECK(theta <= exact * (1 + 1e-12));
  CHECK(exact - theta <= 1e-6 * exact);
  CHECK(energy_iterations < exact_iterations);
  VecDestroy(&x);
}
