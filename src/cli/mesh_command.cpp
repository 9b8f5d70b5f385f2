// contactqp mesh SCENE.json -o BODY.msh: the mesh the scene would be solved on, written once so
// that scenes naming it ("shape": "mesh", "file": "BODY.msh") skip Gmsh.
#include <CLI/CLI.hpp>
#include <filesystem>
#include <iostream>

#include "commands.hpp"
#include "contactqp/errors.hpp"
#include "contactqp/mesh_file.hpp"

namespace contactqp::cli {
namespace {

struct MeshArguments {
  std::string scene_path, output_path;
  long long max_elements = BuildOptions{}.max_elements;
};

int run_mesh(const MeshArguments& arguments) {
  if (std::filesystem::path(arguments.output_path).extension() != ".msh")
    throw InputError("-o", "= " + arguments.output_path + ": must end in .msh (a Gmsh mesh file)");
  check_output_path(arguments.output_path, "-o");
  check_distinct_outputs(arguments.scene_path, {{"-o", arguments.output_path}});
  require(arguments.max_elements > 0, "--max-elements", arguments.max_elements, "must be positive");
  const Scene scene = load_scene(arguments.scene_path);
  if (scene.body.shape == "mesh")
    throw InputError("body.shape", "= \"mesh\": the scene's body is already the file " + scene.body.file);
  BuildOptions options;
  options.max_elements = arguments.max_elements;
  const Mesh mesh = scene_mesh(scene, options);
  write_mesh_file(mesh, arguments.output_path);
  std::cout << mesh.n_nodes() << " nodes, " << mesh.n_elements() << " " << to_string(mesh.type()) << " elements ("
            << mesh.n_dofs() << " DOFs before boundary conditions) written to " << arguments.output_path << "\n";
  return 0;
}

}  // namespace

void add_mesh_command(CLI::App& app, int& exit_status) {
  auto arguments = std::make_shared<MeshArguments>();
  CLI::App* command = app.add_subcommand(
      "mesh", "Write the mesh a scene is solved on to a Gmsh .msh file, for scenes that name it (\"shape\": \"mesh\")");
  command->add_option("scene", arguments->scene_path, "Scene file (JSON)")->required();
  refuse_empty(command->add_option("-o,--output", arguments->output_path, "The .msh file to write"))->required();
  command->add_option("--max-elements", arguments->max_elements, "Refuse meshes with more elements (default 4000000)");
  command->callback([arguments, &exit_status] { exit_status = run_mesh(*arguments); });
}

}  // namespace contactqp::cli
