// read_msh_file (msh_reader.hpp): Gmsh .msh 2.2 and 4.1, ASCII and binary, into a MeshFileData.
#include "msh_reader.hpp"

#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <map>
#include <set>
#include <unordered_set>

#include "contactqp/errors.hpp"
#include "scene/input_file.hpp"

namespace contactqp::detail {
namespace {

// The bytes of a .msh file with a position in them. ASCII numbers are whitespace-separated
// tokens; binary ones are read as the file's native little-endian values.
class Reader {
 public:
  Reader(const std::string& bytes, const std::string& path) : bytes_(bytes), path_(path) {}

  [[noreturn]] void fail(const std::string& what) const { throw InputError(path_, what); }
  size_t remaining() const { return bytes_.size() - position_; }
  bool at_end() {
    skip_space();
    return position_ >= bytes_.size();
  }

  void skip_space() {
    while (position_ < bytes_.size() && std::isspace(static_cast<unsigned char>(bytes_[position_]))) ++position_;
  }

  // The next whitespace-separated word; `what` says what was expected, for the message.
  std::string_view word(const std::string& what) {
    skip_space();
    if (position_ >= bytes_.size()) fail("ends where " + what + " should be");
    const size_t start = position_;
    while (position_ < bytes_.size() && !std::isspace(static_cast<unsigned char>(bytes_[position_]))) ++position_;
    return std::string_view(bytes_).substr(start, position_ - start);
  }

  // An ASCII integer in [low, high].
  long long integer(const std::string& what, long long low, long long high) {
    const std::string_view text = word(what);
    long long value = 0;
    const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (error != std::errc() || end != text.data() + text.size() || value < low || value > high)
      fail("has \"" + printable(text) + "\" where " + what + " should be (an integer from " + std::to_string(low) +
           " to " + std::to_string(high) + ")");
    return value;
  }

  // An ASCII number, finite.
  double real(const std::string& what) {
    const std::string_view text = word(what);
    double value = 0;
    const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (error != std::errc() || end != text.data() + text.size())
      fail("has \"" + printable(text) + "\" where " + what + " should be (a number)");
    if (!std::isfinite(value)) fail("has " + what + " = " + printable(text) + ": not a finite number");
    return value;
  }

  // A quoted name on the rest of the line ("top surface").
  std::string quoted(const std::string& what) {
    skip_space();
    if (position_ >= bytes_.size() || bytes_[position_] != '"') fail("has no quoted name where " + what + " should be");
    const size_t end = bytes_.find_first_of("\"\n", position_ + 1);
    if (end == std::string::npos || bytes_[end] != '"') fail("has an unterminated name where " + what + " should be");
    std::string name = bytes_.substr(position_ + 1, end - position_ - 1);
    position_ = end + 1;
    return name;
  }

  // Past the end of the current line ("\n" or "\r\n"): where binary data begins.
  void end_of_line(const std::string& what) {
    if (position_ < bytes_.size() && bytes_[position_] == '\r') ++position_;
    if (position_ >= bytes_.size() || bytes_[position_] != '\n') fail("has no line end after " + what);
    ++position_;
  }

  template <class T>
  T binary(const std::string& what) {
    if (remaining() < sizeof(T)) fail("ends inside " + what);
    T value;
    std::memcpy(&value, bytes_.data() + position_, sizeof(T));
    position_ += sizeof(T);
    return value;
  }

  // A binary count in [0, high] whose items of `item_bytes` each the rest of the file can hold.
  size_t binary_count(const std::string& what, size_t item_bytes) {
    const auto count = binary<std::uint64_t>(what);
    require_room(count, item_bytes, what);
    return static_cast<size_t>(count);
  }

  // InputError unless `count` items of at least `item_bytes` fit in what is left of the file:
  // every count is checked before anything is allocated by it.
  void require_room(std::uint64_t count, size_t item_bytes, const std::string& what) const {
    if (item_bytes > 0 && count > remaining() / item_bytes)
      fail("declares " + std::to_string(count) + " " + what + ", more than its remaining " +
           std::to_string(remaining()) + " bytes can hold");
  }

  // The section's end: the word "$EndName".
  void end_of_section(const std::string& name) {
    const std::string end = "$End" + name;
    const std::string_view found = word(end);
    if (found != end) fail("has \"" + printable(found) + "\" where " + end + " should end its $" + name + " section");
  }

  // Past the line "$EndName" of a section this reader does not need.
  void skip_section(const std::string& name) {
    const std::string end = "$End" + name;
    for (size_t at = bytes_.find(end, position_); at != std::string::npos; at = bytes_.find(end, at + 1))
      if (at == 0 || bytes_[at - 1] == '\n') {
        position_ = at + end.size();
        return;
      }
    fail("has a $" + name + " section without " + end);
  }

  static std::string printable(std::string_view text) {
    std::string out(text.substr(0, 40));
    for (char& c : out)
      if (static_cast<unsigned char>(c) < 0x20 || static_cast<unsigned char>(c) >= 0x7f) c = '?';
    return text.size() > 40 ? out + "..." : out;
  }

 private:
  const std::string& bytes_;
  const std::string& path_;
  size_t position_ = 0;
};

constexpr long long kIntMax = std::numeric_limits<int>::max();
constexpr long long kTagMax = std::numeric_limits<long long>::max();

// What the sections give, before it becomes a MeshFileData.
struct Contents {
  MeshFileData data;
  std::map<std::pair<int, int>, std::set<int>> groups;  // (dim, physical tag) -> entities
  std::map<std::pair<int, int>, std::string> names;     // (dim, physical tag) -> name
  bool nodes = false, elements = false;
};

const GmshElementType& element_type(Reader& in, long long type, const std::string& element) {
  const GmshElementType* known = gmsh_element_type(static_cast<int>(type));
  if (!known || type != known->type)
    in.fail("has " + element + " of Gmsh element type " + std::to_string(type) +
            ", which contactqp does not read (types 1 to 19: lines, triangles, quadrangles, tetrahedra, hexahedra, "
            "prisms, pyramids, points)");
  return *known;
}

// The elements of one entity and type go to the entity's last block when it has that type.
ElementBlock& block_for(Contents& contents, int dim, int entity, int type) {
  std::vector<ElementBlock>& blocks = contents.data.elements[{dim, entity}];
  if (blocks.empty() || blocks.back().type != type) {
    blocks.emplace_back();
    blocks.back().type = type;
  }
  return blocks.back();
}

void read_physical_names(Reader& in, Contents& contents) {
  const long long n = in.integer("the number of physical names", 0, kIntMax);
  in.require_room(static_cast<std::uint64_t>(n), 8, "physical names");
  for (long long i = 0; i < n; ++i) {
    const int dim = static_cast<int>(in.integer("a physical name's dimension", 0, 3));
    const int tag = static_cast<int>(in.integer("a physical name's tag", -kIntMax, kIntMax));
    contents.names[{dim, tag}] = in.quoted("a physical name");
  }
  in.end_of_section("PhysicalNames");
}

// Version 2.2: "$Nodes", the count on a line, then per node its tag and x y z (binary: an int
// and three doubles).
void read_nodes_22(Reader& in, Contents& contents, bool binary) {
  const long long n = in.integer("the number of nodes", 0, kTagMax);
  in.require_room(static_cast<std::uint64_t>(n), binary ? 28 : 8, "nodes");
  if (binary) in.end_of_line("the number of nodes");
  MeshFileData& data = contents.data;
  data.node_tags.reserve(data.node_tags.size() + n);
  data.coordinates.reserve(data.coordinates.size() + 3 * n);
  for (long long i = 0; i < n; ++i) {
    const long long tag = binary ? in.binary<std::int32_t>("$Nodes") : in.integer("a node tag", 1, kTagMax);
    if (tag < 1) in.fail("has node tag " + std::to_string(tag) + ": tags start at 1");
    data.node_tags.push_back(static_cast<size_t>(tag));
    for (int c = 0; c < 3; ++c) {
      const double x = binary ? in.binary<double>("$Nodes") : in.real("a coordinate of node " + std::to_string(tag));
      if (!std::isfinite(x))
        in.fail("has a coordinate of node " + std::to_string(tag) + " that is not a finite number");
      data.coordinates.push_back(x);
    }
  }
  in.end_of_section("Nodes");
  contents.nodes = true;
}

// Version 2.2: "$Elements", the count, then per element its tag, type, tags (physical group,
// entity, ...) and nodes (binary: blocks of elements of one type with a header of three ints).
void read_elements_22(Reader& in, Contents& contents, bool binary) {
  const long long n = in.integer("the number of elements", 0, kTagMax);
  in.require_room(static_cast<std::uint64_t>(n), binary ? 12 : 8, "elements");
  if (binary) in.end_of_line("the number of elements");
  constexpr long long kMaxTags = 64;
  auto add = [&](long long tag, const GmshElementType& type, const std::vector<long long>& tags,
                 const std::vector<size_t>& nodes) {
    const int physical = tags.size() > 0 ? static_cast<int>(tags[0]) : 0;
    const int entity = tags.size() > 1 ? static_cast<int>(tags[1]) : 0;
    ElementBlock& block = block_for(contents, type.dim, entity, type.type);
    block.tags.push_back(static_cast<size_t>(tag));
    block.nodes.insert(block.nodes.end(), nodes.begin(), nodes.end());
    if (physical != 0) contents.groups[{type.dim, physical}].insert(entity);
  };
  std::vector<long long> tags;
  std::vector<size_t> nodes;
  for (long long read = 0; read < n;) {
    if (binary) {
      const auto type_number = in.binary<std::int32_t>("$Elements");
      const auto count = in.binary<std::int32_t>("$Elements");
      const auto n_tags = in.binary<std::int32_t>("$Elements");
      const GmshElementType& type = element_type(in, type_number, "a block of elements");
      if (count < 1 || count > n - read)
        in.fail("has a block of " + std::to_string(count) + " elements where " + std::to_string(n - read) +
                " are left of the " + std::to_string(n) + " it declares");
      if (n_tags < 0 || n_tags > kMaxTags) in.fail("has elements with " + std::to_string(n_tags) + " tags");
      in.require_room(static_cast<std::uint64_t>(count), 4 * (1 + n_tags + type.n_nodes), "elements");
      for (int i = 0; i < count; ++i, ++read) {
        const long long tag = in.binary<std::int32_t>("$Elements");
        tags.assign(n_tags, 0);
        for (auto& t : tags) t = in.binary<std::int32_t>("$Elements");
        nodes.assign(type.n_nodes, 0);
        for (auto& node : nodes)
          node = static_cast<size_t>(static_cast<std::uint32_t>(in.binary<std::int32_t>("$Elements")));
        add(tag, type, tags, nodes);
      }
    } else {
      const long long tag = in.integer("an element tag", 1, kTagMax);
      const std::string element = "element " + std::to_string(tag);
      const GmshElementType& type = element_type(in, in.integer("the type of " + element, 0, kIntMax), element);
      tags.assign(in.integer("the number of tags of " + element, 0, kMaxTags), 0);
      for (auto& t : tags) t = in.integer("a tag of " + element, -kIntMax, kIntMax);
      nodes.assign(type.n_nodes, 0);
      for (auto& node : nodes) node = static_cast<size_t>(in.integer("a node of " + element, 1, kTagMax));
      add(tag, type, tags, nodes);
      ++read;
    }
  }
  in.end_of_section("Elements");
  contents.elements = true;
}

// Version 4.1 reads sizes as 8-byte unsigned integers, tags as 4-byte ints (binary) — or both
// as ASCII words.
struct Format41 {
  // Binary data begins on the line after the section's name.
  Format41(Reader& reader, bool is_binary, const std::string& section) : in(reader), binary(is_binary) {
    if (binary) in.end_of_line("$" + section);
  }
  Reader& in;
  bool binary;
  long long count(const std::string& what, size_t item_bytes) {
    if (binary) return static_cast<long long>(in.binary_count(what, item_bytes));
    const long long n = in.integer("the number of " + what, 0, kTagMax);
    in.require_room(static_cast<std::uint64_t>(n), 2, what);
    return n;
  }
  int tag(const std::string& what, long long low = -kIntMax) {
    if (binary) {
      const auto value = in.binary<std::int32_t>(what);
      if (value < low) in.fail("has " + what + " = " + std::to_string(value));
      return value;
    }
    return static_cast<int>(in.integer(what, low, kIntMax));
  }
  size_t size_tag(const std::string& what) {
    if (!binary) return static_cast<size_t>(in.integer(what, 1, kTagMax));
    const auto value = in.binary<std::uint64_t>(what);
    if (value < 1) in.fail("has " + what + " = 0: tags start at 1");
    return static_cast<size_t>(value);
  }
  double real(const std::string& what) {
    if (!binary) return in.real(what);
    const double value = in.binary<double>(what);
    if (!std::isfinite(value)) in.fail("has " + what + " that is not a finite number");
    return value;
  }
};

void read_entities_41(Reader& in, Contents& contents, bool binary) {
  Format41 f(in, binary, "Entities");
  long long n[4];
  for (int dim = 0; dim < 4; ++dim) n[dim] = f.count("entities", binary ? 4 : 2);
  for (int dim = 0; dim < 4; ++dim) {
    for (long long i = 0; i < n[dim]; ++i) {
      const int tag = f.tag("an entity tag");
      contents.data.elements[{dim, tag}];  // an entity, with elements or not
      for (int k = 0; k < (dim == 0 ? 3 : 6); ++k) f.real("a bounding coordinate");
      const long long n_physical = f.count("physical tags", binary ? 4 : 2);
      for (long long p = 0; p < n_physical; ++p) {
        const int physical = f.tag("a physical tag");
        if (physical != 0) contents.groups[{dim, physical}].insert(tag);
      }
      if (dim > 0) {
        const long long n_bounding = f.count("bounding entities", binary ? 4 : 2);
        for (long long b = 0; b < n_bounding; ++b) f.tag("a bounding entity");
      }
    }
  }
  in.end_of_section("Entities");
}

void read_nodes_41(Reader& in, Contents& contents, bool binary) {
  Format41 f(in, binary, "Nodes");
  const long long n_blocks = f.count("node blocks", binary ? 20 : 8);
  const long long n_nodes = f.count("nodes", binary ? 32 : 8);
  f.count("", 0);  // the smallest and largest node tags: not needed
  f.count("", 0);
  MeshFileData& data = contents.data;
  data.node_tags.reserve(data.node_tags.size() + n_nodes);
  data.coordinates.reserve(data.coordinates.size() + 3 * n_nodes);
  long long total = 0;
  for (long long b = 0; b < n_blocks; ++b) {
    const int dim = f.tag("a node block's entity dimension", 0);
    if (dim > 3) in.fail("has a node block of dimension " + std::to_string(dim));
    const int entity = f.tag("a node block's entity");
    const int parametric = f.tag("a node block's parametric flag", 0);
    if (parametric > 1) in.fail("has a node block with parametric flag " + std::to_string(parametric));
    const int per_node = 3 + (parametric ? dim : 0);
    const long long n = f.count("nodes", binary ? 8 + 8 * per_node : 2 + 2 * per_node);
    if (n > n_nodes - total)
      in.fail("has node blocks holding more than the " + std::to_string(n_nodes) + " nodes it declares");
    total += n;
    data.elements[{dim, entity}];
    const size_t first = data.node_tags.size();
    for (long long i = 0; i < n; ++i) data.node_tags.push_back(f.size_tag("a node tag"));
    for (long long i = 0; i < n; ++i)
      for (int c = 0; c < per_node; ++c) {
        const double x = f.real("a coordinate of node " + std::to_string(data.node_tags[first + i]));
        if (c < 3) data.coordinates.push_back(x);
      }
    if (dim == 0) {
      std::vector<size_t>& points = data.point_nodes[entity];
      points.insert(points.end(), data.node_tags.begin() + first, data.node_tags.end());
    }
  }
  if (total != n_nodes)
    in.fail("declares " + std::to_string(n_nodes) + " nodes but its blocks hold " + std::to_string(total));
  in.end_of_section("Nodes");
  contents.nodes = true;
}

void read_elements_41(Reader& in, Contents& contents, bool binary) {
  Format41 f(in, binary, "Elements");
  const long long n_blocks = f.count("element blocks", binary ? 20 : 8);
  const long long n_elements = f.count("elements", binary ? 16 : 4);
  f.count("", 0);  // the smallest and largest element tags
  f.count("", 0);
  long long total = 0;
  for (long long b = 0; b < n_blocks; ++b) {
    const int dim = f.tag("an element block's entity dimension", 0);
    if (dim > 3) in.fail("has an element block of dimension " + std::to_string(dim));
    const int entity = f.tag("an element block's entity");
    const GmshElementType& type = element_type(in, f.tag("an element block's type", 0), "a block of elements");
    if (type.dim != dim)
      in.fail("has " + std::string(type.name) + " elements in an entity of dimension " + std::to_string(dim));
    const long long n = f.count("elements", binary ? 8 * (1 + type.n_nodes) : 2 * (1 + type.n_nodes));
    if (n > n_elements - total)
      in.fail("has element blocks holding more than the " + std::to_string(n_elements) + " elements it declares");
    total += n;
    ElementBlock& block = block_for(contents, dim, entity, type.type);
    block.tags.reserve(block.tags.size() + n);
    block.nodes.reserve(block.nodes.size() + n * type.n_nodes);
    for (long long i = 0; i < n; ++i) {
      block.tags.push_back(f.size_tag("an element tag"));
      for (int k = 0; k < type.n_nodes; ++k)
        block.nodes.push_back(f.size_tag("a node of element " + std::to_string(block.tags.back())));
    }
  }
  if (total != n_elements)
    in.fail("declares " + std::to_string(n_elements) + " elements but its blocks hold " + std::to_string(total));
  in.end_of_section("Elements");
  contents.elements = true;
}

}  // namespace

MeshFileData parse_msh(const std::string& bytes, const std::string& path) {
  Reader in(bytes, path);
  // Gmsh's header: "$MeshFormat", then "VERSION FILE-TYPE DATA-SIZE" (0 ASCII, 1 binary; 8-byte
  // numbers), then in a binary file the int 1, which tells the byte order.
  if (in.at_end() || in.word("$MeshFormat") != "$MeshFormat")
    in.fail("is not a Gmsh mesh file: its first line must be $MeshFormat (a .msh of version 2.2 or 4.1)");
  const std::string version(in.word("the format version"));
  const std::string file_type(in.word("the file type"));
  const std::string data_size(in.word("the data size"));
  if ((version != "2.2" && version != "4.1") || (file_type != "0" && file_type != "1") || data_size != "8")
    in.fail("has the format line \"" + Reader::printable(version + " " + file_type + " " + data_size) +
            "\": contactqp reads .msh versions 2.2 and 4.1, ASCII or binary, with 8-byte numbers (\"2.2 0 8\", "
            "\"4.1 1 8\"); convert with gmsh FILE -save -format msh41");
  const bool binary = file_type == "1", v41 = version == "4.1";
  if (binary) {
    in.end_of_line("the format line");
    if (in.binary<std::int32_t>("$MeshFormat") != 1)
      in.fail("is a binary .msh of the other byte order (written on a big-endian machine); save it as ASCII");
  }
  in.end_of_section("MeshFormat");

  Contents contents;
  while (!in.at_end()) {
    const std::string_view header = in.word("a section");
    if (header.size() < 2 || header[0] != '$')
      in.fail("has \"" + Reader::printable(header) + "\" where a section ($Nodes, $Elements, ...) should begin");
    const std::string name(header.substr(1));
    if (name == "PhysicalNames") {
      read_physical_names(in, contents);
    } else if (name == "Entities" && v41) {
      read_entities_41(in, contents, binary);
    } else if (name == "Nodes" && !contents.nodes) {
      v41 ? read_nodes_41(in, contents, binary) : read_nodes_22(in, contents, binary);
    } else if (name == "Elements" && !contents.elements) {
      v41 ? read_elements_41(in, contents, binary) : read_elements_22(in, contents, binary);
    } else if (name == "Nodes" || name == "Elements") {
      in.fail("has a second $" + name + " section");
    } else {
      in.skip_section(name);
    }
  }
  if (!contents.nodes) in.fail("has no $Nodes section");
  if (!contents.elements) in.fail("has no $Elements section");

  MeshFileData& data = contents.data;
  std::unordered_set<size_t> seen;
  seen.reserve(data.node_tags.size());
  for (size_t tag : data.node_tags)
    if (!seen.insert(tag).second) in.fail("defines node " + std::to_string(tag) + " twice");
  for (const auto& [key, entities] : contents.groups) {
    MeshFileData::PhysicalGroup group;
    group.dim = key.first;
    group.tag = key.second;
    const auto name = contents.names.find(key);
    if (name != contents.names.end()) group.name = name->second;
    group.entities.assign(entities.begin(), entities.end());
    data.groups.push_back(std::move(group));
  }
  return std::move(contents.data);
}

MeshFileData read_msh_file(const std::string& path) { return parse_msh(read_input_file(path, "mesh file"), path); }

}  // namespace contactqp::detail
