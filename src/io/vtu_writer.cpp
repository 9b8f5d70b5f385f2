// ParaView output: the mesh and the solution as a VTK XML unstructured grid with binary
// (base64) arrays, which VTK and ParaView read directly.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <string>

#include "contact/contact.hpp"
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

// VTK's inline binary block: base64 of a UInt64 byte count followed by the data, encoded as one
// stream, appended to `out` in place (the block is never copied whole: a 1e6-DOF file has
// 1.1e8 bytes of arrays).
void append_binary_block(std::string& out, const void* data, std::uint64_t bytes) {
  static const char kAlphabet[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  const std::uint64_t total = sizeof bytes + bytes;
  const std::size_t start = out.size();
  out.resize(start + 4 * ((total + 2) / 3));
  char* to = out.data() + start;
  // The count's 8 bytes and the data's first one make three full groups; then the data alone.
  unsigned char head[9] = {};
  std::memcpy(head, &bytes, sizeof bytes);
  const auto* from = static_cast<const unsigned char*>(data);
  std::uint64_t used = 0;  // data bytes already in `head`
  if (bytes) head[8] = from[used++];
  auto put = [&to](std::uint32_t chunk, int significant) {
    to[0] = kAlphabet[(chunk >> 18) & 63];
    to[1] = kAlphabet[(chunk >> 12) & 63];
    to[2] = significant > 1 ? kAlphabet[(chunk >> 6) & 63] : '=';
    to[3] = significant > 2 ? kAlphabet[chunk & 63] : '=';
    to += 4;
  };
  const int head_bytes = bytes ? 9 : 8;
  for (int i = 0; i < head_bytes; i += 3) {
    const int n = std::min(3, head_bytes - i);
    put((std::uint32_t(head[i]) << 16) | (n > 1 ? std::uint32_t(head[i + 1]) << 8 : 0) |
            (n > 2 ? std::uint32_t(head[i + 2]) : 0),
        n);
  }
  if (bytes <= used) return;  // an empty array (from may be null) or a one-byte one
  const std::uint64_t rest = bytes - used, full = rest / 3 * 3;
  const unsigned char* p = from + used;
  for (std::uint64_t i = 0; i < full; i += 3, p += 3)
    put((std::uint32_t(p[0]) << 16) | (std::uint32_t(p[1]) << 8) | std::uint32_t(p[2]), 3);
  if (rest > full)
    put((std::uint32_t(p[0]) << 16) | (rest - full > 1 ? std::uint32_t(p[1]) << 8 : 0), int(rest - full));
}

// One <DataArray> in VTK's inline binary format, appended to `out`.
template <class T>
void data_array(std::string& out, const char* type, const std::string& name, int components, const T* values,
                std::size_t count) {
  out += "        <DataArray type=\"";
  out += type;
  out += "\" Name=\"" + name + "\" NumberOfComponents=\"" + std::to_string(components) +
         "\" format=\"binary\">\n          ";
  append_binary_block(out, values, count * sizeof(T));
  out += "\n        </DataArray>\n";
}

// A nodal vector field of dim components per node as 3 components (z = 0 in 2D), as
// ParaView's vector filters expect.
PointArray vector_array(const std::string& name, const Eigen::VectorXd& field, int dim) {
  PointArray array{name, 3, field.data(), {}};
  if (dim == 3) return array;
  const Eigen::Index n = field.size() / dim;
  array.storage.assign(3 * n, 0.0);
  for (Eigen::Index k = 0; k < n; ++k)
    for (int c = 0; c < dim; ++c) array.storage[3 * k + c] = field[dim * k + c];
  array.values = array.storage.data();
  return array;
}

PointArray scalar_array(const std::string& name, const Eigen::VectorXd& values) {
  return PointArray{name, 1, values.data(), {}};
}

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

// With friction, at each node of a row's node side: the friction traction and this step's slip
// (vectors, the sums over the node's rows) and the state (the largest over its rows: 0 gap,
// 1 stick, 2 slip).
struct FrictionNodeFields {
  Eigen::VectorXd traction, slip, state;
};

FrictionNodeFields friction_node_fields(const Model& model, const FrictionFields& fields) {
  const int n = model.mesh.n_nodes(), dim = model.dim;
  FrictionNodeFields out{Eigen::VectorXd::Zero(dim * n), Eigen::VectorXd::Zero(dim * n), Eigen::VectorXd::Zero(n)};
  for (size_t i = 0; i < model.candidates.size(); ++i) {
    const int node = model.candidates[i].node;
    out.traction.segment(dim * node, dim) += fields.traction[i].head(dim);
    out.slip.segment(dim * node, dim) += fields.slip[i].head(dim);
    out.state[node] = std::max(out.state[node], static_cast<double>(fields.state[i]));
  }
  return out;
}

}  // namespace

std::string vtu_piece(const Mesh& mesh, const std::vector<PointArray>& arrays,
                      const std::vector<PointArray>& cell_arrays) {
  std::vector<double> points(3 * mesh.n_nodes(), 0.0);
  for (int k = 0; k < mesh.n_nodes(); ++k)
    for (int c = 0; c < 3; ++c) points[3 * k + c] = mesh.nodes[k][c];
  const int npe = mesh.nodes_per_element();
  std::vector<std::int64_t> connectivity(mesh.elements.begin(), mesh.elements.end()), offsets(mesh.n_elements());
  for (int e = 0; e < mesh.n_elements(); ++e) offsets[e] = static_cast<std::int64_t>(npe) * (e + 1);
  const std::vector<std::uint8_t> types(mesh.n_elements(), vtk_cell_type(mesh.type()));
  const std::size_t n = static_cast<std::size_t>(mesh.n_nodes()), n_cells = static_cast<std::size_t>(mesh.n_elements());
  // The arrays' bytes (in base64, 4 characters per 3 bytes) and some for the markup: one allocation.
  std::size_t n_values = 3 * n;
  for (const PointArray& array : arrays) n_values += array.components * n;
  for (const PointArray& array : cell_arrays) n_values += array.components * n_cells;
  const std::size_t array_bytes = 8 * n_values + 8 * (connectivity.size() + offsets.size()) + n_cells;
  std::string out;
  out.reserve(4 * array_bytes / 3 + 4096);
  out += "<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"";
  out += byte_order();
  out += "\" header_type=\"UInt64\">\n  <UnstructuredGrid>\n    <Piece NumberOfPoints=\"" + std::to_string(n) +
         "\" NumberOfCells=\"" + std::to_string(n_cells) + "\">\n" +
         "      <PointData Scalars=\"von_mises\" Vectors=\"displacement\">\n";
  for (const PointArray& array : arrays)
    data_array(out, "Float64", array.name, array.components, array.values, array.components * n);
  out += "      </PointData>\n";
  if (!cell_arrays.empty()) {
    out += "      <CellData>\n";
    for (const PointArray& array : cell_arrays)
      data_array(out, "Float64", array.name, array.components, array.values, array.components * n_cells);
    out += "      </CellData>\n";
  }
  out += "      <Points>\n";
  data_array(out, "Float64", "Points", 3, points.data(), points.size());
  out += "      </Points>\n      <Cells>\n";
  data_array(out, "Int64", "connectivity", 1, connectivity.data(), connectivity.size());
  data_array(out, "Int64", "offsets", 1, offsets.data(), offsets.size());
  data_array(out, "UInt8", "types", 1, types.data(), types.size());
  out += "      </Cells>\n    </Piece>\n  </UnstructuredGrid>\n</VTKFile>\n";
  return out;
}

std::string pvtu_document(const std::vector<PointArray>& arrays, const std::vector<std::string>& pieces,
                          const std::vector<PointArray>& cell_arrays) {
  std::string out = "<?xml version=\"1.0\"?>\n<VTKFile type=\"PUnstructuredGrid\" version=\"1.0\" byte_order=\"";
  out += byte_order();
  out += "\" header_type=\"UInt64\">\n  <PUnstructuredGrid GhostLevel=\"0\">\n";
  out += "    <PPointData Scalars=\"von_mises\" Vectors=\"displacement\">\n";
  for (const PointArray& array : arrays)
    out += "      <PDataArray type=\"Float64\" Name=\"" + array.name + "\" NumberOfComponents=\"" +
           std::to_string(array.components) + "\"/>\n";
  out += "    </PPointData>\n";
  if (!cell_arrays.empty()) {
    out += "    <PCellData>\n";
    for (const PointArray& array : cell_arrays)
      out += "      <PDataArray type=\"Float64\" Name=\"" + array.name + "\" NumberOfComponents=\"" +
             std::to_string(array.components) + "\"/>\n";
    out += "    </PCellData>\n";
  }
  out +=
      "    <PPoints>\n      <PDataArray type=\"Float64\" Name=\"Points\" "
      "NumberOfComponents=\"3\"/>\n"
      "    </PPoints>\n    <PCells>\n"
      "      <PDataArray type=\"Int64\" Name=\"connectivity\" NumberOfComponents=\"1\"/>\n"
      "      <PDataArray type=\"Int64\" Name=\"offsets\" NumberOfComponents=\"1\"/>\n"
      "      <PDataArray type=\"UInt8\" Name=\"types\" NumberOfComponents=\"1\"/>\n    </PCells>\n";
  for (const std::string& piece : pieces) out += "    <Piece Source=\"" + piece + "\"/>\n";
  out += "  </PUnstructuredGrid>\n</VTKFile>\n";
  return out;
}

std::vector<PointArray> solution_arrays(const Model& model, const Eigen::VectorXd& displacement,
                                        const NodalStress& stress, const ContactFields& contact,
                                        const Eigen::VectorXd* body) {
  const int dim = model.dim;
  std::vector<PointArray> arrays;
  arrays.push_back(vector_array("displacement", displacement, dim));
  arrays.push_back(scalar_array("sigma_xx", stress.xx));
  arrays.push_back(scalar_array("sigma_yy", stress.yy));
  arrays.push_back(scalar_array("sigma_xy", stress.xy));
  arrays.push_back(scalar_array("sigma_zz", stress.zz));
  if (dim == 3) {
    arrays.push_back(scalar_array("sigma_yz", stress.yz));
    arrays.push_back(scalar_array("sigma_xz", stress.xz));
  }
  arrays.push_back(scalar_array("von_mises", stress.von_mises));
  arrays.push_back(scalar_array("contact_pressure", contact.pressure));
  arrays.push_back(vector_array("contact_force", contact.force, dim));
  arrays.push_back(scalar_array("gap", contact.gap));
  arrays.push_back(scalar_array("contact_boundary", contact.mask));
  if (body) arrays.push_back(scalar_array("body", *body));
  return arrays;
}

std::string vtu_document(const RunReport& report) {
  const Model& model = *report.model;
  const Eigen::VectorXd displacement = full_displacement(model, report.result.u);
  const NodalStress stress = nodal_stresses(model, displacement);
  const ContactFields contact = contact_fields(report, displacement);
  // With several bodies, which body each node belongs to (0, 1, ... in the scene's order).
  Eigen::VectorXd body;
  if (!model.bodies.empty()) {
    body = Eigen::VectorXd::Zero(model.mesh.n_nodes());
    for (size_t b = 0; b < model.bodies.size(); ++b)
      body.segment(model.bodies[b].first_node, model.bodies[b].n_nodes).setConstant(static_cast<double>(b));
  }
  std::vector<PointArray> arrays = solution_arrays(model, displacement, stress, contact);
  // With friction: the friction traction, this step's slip and the state (before "body").
  FrictionNodeFields friction;
  if (report.friction) {
    friction = friction_node_fields(model, *report.friction);
    arrays.push_back(vector_array("tangential_traction", friction.traction, model.dim));
    arrays.push_back(vector_array("slip", friction.slip, model.dim));
    arrays.push_back(scalar_array("contact_state", friction.state));
  }
  if (body.size()) arrays.push_back(scalar_array("body", body));
  std::vector<PointArray> cells;
  if (report.error_estimate && report.error_estimate->indicator.size() == model.mesh.n_elements())
    cells.push_back(scalar_array("error_indicator", report.error_estimate->indicator));
  return vtu_piece(model.mesh, arrays, cells);
}

}  // namespace contactqp
