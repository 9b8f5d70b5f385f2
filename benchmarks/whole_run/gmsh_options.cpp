// Gmsh on the half disc alone (docs/whole-run.md, "Meshing"): CPU time of generate(2) with
// the size field and algorithm varied, and a hash of the node positions (same hash: same mesh).
//   g++ -O2 -o /tmp/gmsh_options benchmarks/whole_run/gmsh_options.cpp -lgmsh
//   /tmp/gmsh_options SIZE CONTACT_SIZE matheval|threshold [ALGORITHM=6] [SMOOTHING=-1: default] [FINE_ANGLE=0.3]
// e.g. 0.004 0.001 matheval 6; 0.004 0.001 threshold 6; 0.004 0.001 matheval 6 0; ... matheval 5; ... matheval 1
#include <gmsh.h>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <functional>
#include <string>
#include <vector>
using clk = std::chrono::steady_clock;
double secs(clk::time_point a) { return std::chrono::duration<double>(clk::now() - a).count(); }
int main(int argc, char** argv) {
  double size = atof(argv[1]), cs = atof(argv[2]);
  std::string variant = argv[3];
  int alg = argc > 4 ? atoi(argv[4]) : 6;
  int smoothing = argc > 5 ? atoi(argv[5]) : -1;
  double grading = 0.1;
  const double kPi = 3.14159265358979323846;
  gmsh::initialize(0, nullptr, false);
  gmsh::option::setNumber("General.Terminal", getenv("V") ? 1 : 0);
  if (getenv("V")) gmsh::option::setNumber("General.Verbosity", atoi(getenv("V")));
  gmsh::model::add("hd");
  namespace geo = gmsh::model::geo;
  auto arc_point = [](double phi) { return geo::addPoint(std::sin(phi), 1.0 - std::cos(phi), 0.0); };
  // symmetric: phi from 0 to pi/2; fine arc: as in the scene? assume fine = [0, phi_f]
  double phi_f = argc > 6 ? atof(argv[6]) : 0.3;
  std::vector<double> breaks = {0.0, phi_f, kPi / 2};
  int centre = geo::addPoint(0, 1, 0);
  std::vector<int> pts;
  for (double p : breaks) pts.push_back(arc_point(p));
  std::vector<int> loop;
  int fine = geo::addCircleArc(pts[0], centre, pts[1]);
  loop.push_back(fine);
  loop.push_back(geo::addCircleArc(pts[1], centre, pts[2]));
  loop.push_back(geo::addLine(pts[2], centre));
  loop.push_back(geo::addLine(centre, pts[0]));
  geo::addPlaneSurface({geo::addCurveLoop(loop)});
  geo::synchronize();
  namespace field = gmsh::model::mesh::field;
  int d = field::add("Distance");
  field::setNumbers(d, "CurvesList", {double(fine)});
  field::setNumber(d, "NumPointsPerCurve", std::max(20.0, 4.0 * phi_f / cs));
  if (variant == "matheval") {
    int f = field::add("MathEval");
    char e[256];
    snprintf(e, sizeof e, "Min(%.17g, %.17g + %.17g * F%d)", size, cs, grading, d);
    field::setString(f, "F", e);
    field::setAsBackgroundMesh(f);
  } else if (variant == "threshold") {
    int f = field::add("Threshold");
    field::setNumber(f, "InField", d);
    field::setNumber(f, "SizeMin", cs);
    field::setNumber(f, "SizeMax", size);
    field::setNumber(f, "DistMin", 0);
    field::setNumber(f, "DistMax", (size - cs) / grading);
    field::setAsBackgroundMesh(f);
  }
  gmsh::option::setNumber("Mesh.MeshSizeExtendFromBoundary", 0);
  gmsh::option::setNumber("Mesh.MeshSizeFromPoints", 0);
  gmsh::option::setNumber("Mesh.MeshSizeFromCurvature", 0);
  gmsh::option::setNumber("Mesh.Algorithm", alg);
  if (smoothing >= 0) gmsh::option::setNumber("Mesh.Smoothing", smoothing);
  auto t = clk::now();
  std::clock_t c0 = std::clock();
  gmsh::model::mesh::generate(2);
  double tg = secs(t);
  double cg = double(std::clock() - c0) / CLOCKS_PER_SEC;
  std::vector<std::size_t> tags;
  std::vector<double> xyz, par;
  gmsh::model::mesh::getNodes(tags, xyz, par);
  double h = 0;
  for (size_t k = 0; k < xyz.size(); ++k) h += xyz[k] * (1 + (k % 7));
  printf("%s alg=%d smooth=%d nodes=%zu gen=%.3f s cpu=%.3f hash=%.17g\n", variant.c_str(), alg, smoothing, tags.size(),
         tg, cg, h);
  gmsh::finalize();
}
