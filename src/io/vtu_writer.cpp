// ParaView output: the mesh and the solution as a VTK XML unstructured grid with binary
// (base64) arrays, which VTK and ParaView read directly.
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <sstream>

#include "../contact/contact.hpp"
#include "contactqp/io.hpp"

namespace contactqp {
namespace {

constexpr std::uint8_t kVtkTriangle = 5, kVtkQuadraticTriangle = 22, kVtkTetra = 10, kVtkQuadraticTetra = 24;

std::uint8_t vtk_cell_type(ElementType type) {
  switch (type) {
    case ElementType::Tri3:
      return kVtkTriangle;
    case ElementType::Tri6:
      return kVtkQuadraticTriangle;
    case ElementType::Tet4:
      return kVtkTetra;
    case ElementType::Tet10:
      return kVtkQuadraticTetra;  // our node order is VTK's
  }
  return kVtkTriangle;
}

const char* byte_order() {
  const std::uint16_t probe = 1;
  unsigned char first = 0;
  std::memcpy(&first, &probe, 1);
  return first == 1 ? "LittleEndian" : "BigEndian";
}

std::string base64(const unsigned char* data, std::size_t size) {
  static const char kAlphabet[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve(4 * ((size + 2) / 3));
  for (std::size_t i = 0; i < size; i += 3) {
    const std::uint32_t chunk = (std::uint32_t(data[i]) << 16) | (i + 1 < size ? std::uint32_t(data[i + 1]) << 8 : 0) |
                                (i + 2 < size ? std::uint32_t(data[i + 2]) : 0);
    out += kAlphabet[(chunk >> 18) & 63];
    out += kAlphabet[(chunk >> 12) & 63];
    out += i + 1 < size ? kAlphabet[(chunk >> 6) & 63] : '=';
    out += i + 2 < size ? kAlphabet[chunk & 63] : '=';
  }
  return out;
}

// One <DataArray> in VTK's inline binary format: base64 of a UInt64 byte count, then the data.
template <class T>
std::string data_array(const std::string& type, const std::string& name, int components, const std::vector<T>& values) {
  const std::uint64_t bytes = values.size() * sizeof(T);
  std::vector<unsigned char> block(sizeof bytes + bytes);
  std::memcpy(block.data(), &bytes, sizeof bytes);
  if (bytes) std::memcpy(block.data() + sizeof bytes, values.data(), bytes);
  std::ostringstream out;
  out << "        <DataArray type=\"" << type << "\" Name=\"" << name << "\" NumberOfComponents=\"" << components
      << "\" format=\"binary\">\n          " << base64(block.data(), block.size()) << "\n        </DataArray>\n";
  return out.str();
}

std::string scalars(const std::string& name, const Eigen::VectorXd& values) {
  return data_array("Float64", name, 1, std::vector<double>(values.data(), values.data() + values.size()));
}

// A nodal vector field of dim components per node as 3 components (z = 0 in 2D), as
// ParaView's vector filters expect.
std::string vectors(const std::string& name, const Eigen::VectorXd& field, int dim) {
  const Eigen::Index n = field.size() / dim;
  std::vector<double> xyz(3 * n, 0.0);
  for (Eigen::Index k = 0; k < n; ++k)
    for (int c = 0; c < dim; ++c) xyz[3 * k + c] = field[dim * k + c];
  return data_array("Float64", name, 3, xyz);
}

// Pressure, contact force, gap and the contact-boundary mask at every node.
struct ContactFields {
  Eigen::VectorXd pressure, force, gap, mask;
};

ContactFields contact_fields(const RunReport& report, const Eigen::VectorXd& displacement) {
  const Model& model = *report.model;
  const QuadraticProgram& qp = *report.qp;
  const int n = model.mesh.n_nodes();
  const int dim = model.dim;
  ContactFields fields{Eigen::VectorXd::Zero(n), Eigen::VectorXd::Zero(dim * n), Eigen::VectorXd::Zero(n),
                       Eigen::VectorXd::Zero(n)};
  const Eigen::VectorXd& lambda = report.result.lambda;
  const Eigen::VectorXd slack = qp.g - qp.B * report.result.u;
  std::vector<bool> candidate(n, false);
  const double infinity = std::numeric_limits<double>::infinity();
  Eigen::VectorXd gap = Eigen::VectorXd::Constant(n, infinity);
  const std::vector<double> pressure = nodal_pressures(model, qp, lambda);
  for (int i = 0; i < qp.n_constraints(); ++i) {
    const Candidate& c = model.candidates[i];
    fields.pressure[c.node] += pressure[i];
    gap[c.node] = std::min(gap[c.node], slack[i]);
    candidate[c.node] = true;
  }
  fields.force = contact_nodal_forces(model, qp, lambda);
  // Between bodies the face side's nodes have the pressure of their share of the rows' forces.
  for (const PairContact& pair : report.pairs) {
    for (const ContactProfilePoint& point : pair.face_profile) fields.pressure[point.node] += point.pressure;
    for (int node : boundary_nodes(model.mesh, pair.node_side)) fields.mask[node] = 1;
    for (int node : boundary_nodes(model.mesh, pair.face_side)) fields.mask[node] = 1;
  }
  for (int node : boundary_nodes(model.mesh, model.scene.contact.boundary)) {
    fields.mask[node] = 1;
    if (candidate[node]) continue;
    Eigen::Vector3d moved = model.mesh.nodes[node];
    moved.head(dim) += displacement.segment(dim * node, dim);
    for (const ObstacleSpec& obstacle : model.scene.obstacles)
      gap[node] = std::min(gap[node], detail::project(obstacle, moved).gap);
  }
  for (int k = 0; k < n; ++k) fields.gap[k] = std::isfinite(gap[k]) ? gap[k] : 0.0;
  return fields;
}

}  // namespace

std::string vtu_document(const RunReport& report) {
  const Model& model = *report.model;
  const Mesh& mesh = model.mesh;
  const Eigen::VectorXd displacement = full_displacement(model, report.result.u);
  const NodalStress stress = nodal_stresses(model, displacement);
  const ContactFields contact = contact_fields(report, displacement);

  std::vector<double> points(3 * mesh.n_nodes(), 0.0);
  for (int k = 0; k < mesh.n_nodes(); ++k)
    for (int c = 0; c < 3; ++c) points[3 * k + c] = mesh.nodes[k][c];
  const int npe = mesh.nodes_per_element();
  std::vector<std::int64_t> connectivity(mesh.elements.begin(), mesh.elements.end()), offsets(mesh.n_elements());
  for (int e = 0; e < mesh.n_elements(); ++e) offsets[e] = static_cast<std::int64_t>(npe) * (e + 1);
  const std::vector<std::uint8_t> types(mesh.n_elements(), vtk_cell_type(mesh.type()));
  const int dim = mesh.dim;
  // With several bodies, which body each node belongs to (0, 1, ... in the scene's order).
  std::string body_array;
  if (!model.bodies.empty()) {
    Eigen::VectorXd body = Eigen::VectorXd::Zero(mesh.n_nodes());
    for (size_t b = 0; b < model.bodies.size(); ++b)
      body.segment(model.bodies[b].first_node, model.bodies[b].n_nodes).setConstant(static_cast<double>(b));
    body_array = scalars("body", body);
  }
  const std::string shear_3d =
      dim == 3 ? scalars("sigma_yz", stress.yz) + scalars("sigma_xz", stress.xz) : std::string();

  std::ostringstream out;
  out << "<?xml version=\"1.0\"?>\n"
      << "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"" << byte_order()
      << "\" header_type=\"UInt64\">\n"
      << "  <UnstructuredGrid>\n"
      << "    <Piece NumberOfPoints=\"" << mesh.n_nodes() << "\" NumberOfCells=\"" << mesh.n_elements() << "\">\n"
      << "      <PointData Scalars=\"von_mises\" Vectors=\"displacement\">\n"
      << vectors("displacement", displacement, dim) << scalars("sigma_xx", stress.xx) << scalars("sigma_yy", stress.yy)
      << scalars("sigma_xy", stress.xy) << scalars("sigma_zz", stress.zz) << shear_3d
      << scalars("von_mises", stress.von_mises) << scalars("contact_pressure", contact.pressure)
      << vectors("contact_force", contact.force, dim) << scalars("gap", contact.gap)
      << scalars("contact_boundary", contact.mask) << body_array << "      </PointData>\n"
      << "      <Points>\n"
      << data_array("Float64", "Points", 3, points) << "      </Points>\n"
      << "      <Cells>\n"
      << data_array("Int64", "connectivity", 1, connectivity) << data_array("Int64", "offsets", 1, offsets)
      << data_array("UInt8", "types", 1, types) << "      </Cells>\n"
      << "    </Piece>\n"
      << "  </UnstructuredGrid>\n"
      << "</VTKFile>\n";
  return out.str();
}

}  // namespace contactqp
