// Tests of the scene output writers: CSV statistics, JSON summary, VTK frames, POV-Ray scenes.
#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "catch_compat.hpp"
#include "gpusolve/rbd/io/csv_writer.hpp"
#include "gpusolve/rbd/io/frame.hpp"
#include "gpusolve/rbd/io/json_writer.hpp"
#include "gpusolve/rbd/io/povray_writer.hpp"
#include "gpusolve/rbd/io/vtk_writer.hpp"
#include "gpusolve/rbd/io/snapshot.hpp"

namespace fs = std::filesystem;
using gpusolve::rbd::io::Frame;

namespace {

fs::path temp_file(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / "gpusolve_test_scene_io";
  fs::create_directories(dir);
  return dir / name;
}

std::vector<std::string> lines_of(const fs::path& p) {
  std::ifstream in(p);
  std::vector<std::string> r;
  for (std::string l; std::getline(in, l);) r.push_back(l);
  return r;
}

std::vector<std::string> split(const std::string& s, char sep) {
  std::vector<std::string> r;
  std::stringstream ss(s);
  for (std::string t; std::getline(ss, t, sep);) r.push_back(t);
  return r;
}

// A strict recursive-descent JSON validator (RFC 8259 grammar, no extensions):
// enough to prove the writer's output parses.
struct JsonCheck {
  const std::string& s;
  std::size_t i = 0;
  void ws() { while (i < s.size() && std::isspace(static_cast<unsigned char>(s[i]))) ++i; }
  bool lit(const char* w) {
    const std::string t(w);
    if (s.compare(i, t.size(), t) != 0) return false;
    i += t.size();
    return true;
  }
  bool str() {
    if (s[i] != '"') return false;
    for (++i; i < s.size(); ++i) {
      if (s[i] == '"') return ++i, true;
      if (static_cast<unsigned char>(s[i]) < 0x20) return false;
      if (s[i] == '\\' && ++i < s.size() && std::string("\"\\/bfnrtu").find(s[i]) == std::string::npos)
        return false;
    }
    return false;
  }
  bool num() {
    const std::size_t b = i;
    if (s[i] == '-') ++i;
    while (i < s.size() && (std::isdigit(static_cast<unsigned char>(s[i])) || std::string(".eE+-").find(s[i]) != std::string::npos)) ++i;
    return i > b && std::isdigit(static_cast<unsigned char>(s[i - 1]));
  }
  bool value() {
    ws();
    if (i >= s.size()) return false;
    bool ok;
    if (s[i] == '{' || s[i] == '[') {
      const char close = s[i] == '{' ? '}' : ']';
      const bool obj = s[i] == '{';
      ++i, ws();
      if (s[i] == close) return ++i, true;
      do {
        ws();
        if (obj && !(str() && (ws(), s[i++] == ':'))) return false;
        if (!value()) return false;
        ws();
      } while (s[i] == ',' && ++i);
      ok = s[i++] == close;
    } else if (s[i] == '"') {
      ok = str();
    } else if (lit("true") || lit("false") || lit("null")) {
      ok = true;
    } else {
      ok = num();
    }
    return ok;
  }
  bool document() { return value() && (ws(), i == s.size()); }
};

bool valid_json(const std::string& s) { return JsonCheck{s}.document(); }

Frame sample_frame() {
  Frame f;
  f.step = 42;
  f.time = 0.105;
  f.add_sphere({0, 0, 1}, 1.0, {0, 0, -2});
  f.add_sphere({3, 0, 1}, 0.5, {1, 0, 0});
  f.add_sphere({0, 3, 1}, 0.75);
  // A box turned 90 degrees about z: its local x axis points along world y.
  f.boxes.push_back({{10, 0, 1}, {2, 1, 0.5}, {0, -1, 0, 1, 0, 0, 0, 0, 1}});
  f.planes.push_back({{0, 0, 1}, 0.0});
  f.planes.push_back({{0, 0, -1}, -10.0});  // a ceiling at z = 10, below the auto camera
  return f;
}

}  // namespace

TEST_CASE("the JSON validator used below rejects malformed documents", "[scene_io]") {
  CHECK(valid_json("{\"a\": [1, -2.5e3, true, null, \"x\\n\"], \"b\": {}}"));
  CHECK_FALSE(valid_json("{\"a\": 1,}"));
  CHECK_FALSE(valid_json("{\"a\" 1}"));
  CHECK_FALSE(valid_json("[1, 2"));
  CHECK_FALSE(valid_json("{\"a\": nan}"));
  CHECK_FALSE(valid_json("[1] [2]"));
}

TEST_CASE("CsvWriter writes a header and rows of equal width", "[scene_io]") {
  const auto path = temp_file("stats.csv");
  {
    gpusolve::rbd::io::CsvWriter csv(path.string(), {"step", "time", "residual"});
    csv.row({0, 0.0, 1e-3});
    csv.row({1, 0.0025, std::nan("")});
    CHECK_THROWS_AS(csv.row({2, 0.005}), gpusolve::SizeMismatchError);
    CHECK(csv.rows() == 2);
  }
  const auto lines = lines_of(path);
  REQUIRE(lines.size() == 3);
  CHECK(lines[0] == "step,time,residual");
  for (const auto& l : lines) CHECK(split(l, ',').size() == 3);
  CHECK(std::stod(split(lines[2], ',')[1]) == Approx(0.0025));
  CHECK(split(lines[2], ',')[2] == "nan");
  CHECK_THROWS_AS(gpusolve::rbd::io::CsvWriter(path.string(), {"a,b"}), gpusolve::InvalidArgumentError);
}

TEST_CASE("JsonWriter produces valid JSON and refuses misuse", "[scene_io]") {
  std::ostringstream os;
  gpusolve::rbd::io::JsonWriter j(os);
  j.begin_object()
      .field("scene", "well \"deep\"\n")
      .field("steps", 20000)
      .field("tolerance", 5e-3)
      .field("diverged", false)
      .field("residual", std::nan(""))
      .begin_object("empty").end_object()
      .begin_array("iterations").value(1).value(2.5).end_array()
      .end_object();
  CHECK(j.done());
  INFO(os.str());
  CHECK(valid_json(os.str()));
  CHECK(os.str().find("\"residual\": null") != std::string::npos);

  std::ostringstream bad;
  gpusolve::rbd::io::JsonWriter k(bad);
  k.begin_array();
  CHECK_THROWS_AS(k.field("a", 1), gpusolve::InvalidArgumentError);
  CHECK_THROWS_AS(k.end_object(), gpusolve::InvalidArgumentError);
  k.end_array();
  CHECK_THROWS_AS(k.value(1), gpusolve::InvalidArgumentError);
}

TEST_CASE("box_corners applies the box rotation", "[scene_io]") {
  const auto c = gpusolve::rbd::io::box_corners(sample_frame().boxes[0]);
  // Corner 1 is local (+hx, -hy, -hz) = (2, -1, -0.5); rotated: (1, 2, -0.5).
  CHECK(c[1][0] == Approx(11.0));
  CHECK(c[1][1] == Approx(2.0));
  CHECK(c[1][2] == Approx(0.5));
  CHECK(c[6][0] == Approx(9.0));
  CHECK(c[6][1] == Approx(2.0));
  CHECK(c[6][2] == Approx(1.5));
}

TEST_CASE("VTK sphere files carry every sphere as a point with its data", "[scene_io]") {
  const Frame f = sample_frame();
  const auto path = temp_file("frame.vtk");
  gpusolve::rbd::io::write_vtk_spheres(path.string(), f);
  const auto lines = lines_of(path);
  REQUIRE(lines.size() > 5);
  CHECK(lines[0] == "# vtk DataFile Version 3.0");
  CHECK(lines[2] == "ASCII");
  CHECK(lines[3] == "DATASET POLYDATA");
  std::size_t points_at = 0;
  for (std::size_t k = 0; k < lines.size(); ++k)
    if (lines[k].rfind("POINTS ", 0) == 0) points_at = k;
  REQUIRE(points_at > 0);
  CHECK(lines[points_at] == "POINTS 3 float");
  CHECK(split(lines[points_at + 2], ' ') == std::vector<std::string>{"3", "0", "1"});
  CHECK(lines[points_at + 4] == "VERTICES 3 6");
  int radius_at = -1, vel_at = -1;
  for (std::size_t k = 0; k < lines.size(); ++k) {
    if (lines[k] == "SCALARS radius float 1") radius_at = static_cast<int>(k);
    if (lines[k] == "VECTORS velocity float") vel_at = static_cast<int>(k);
  }
  REQUIRE(radius_at > 0);
  REQUIRE(vel_at > 0);
  CHECK(std::stod(lines[radius_at + 3]) == Approx(0.5));
  CHECK(split(lines[vel_at + 1], ' ') == std::vector<std::string>{"0", "0", "-2"});

  Frame broken = f;
  broken.spheres.vel.pop_back();
  CHECK_THROWS_AS(gpusolve::rbd::io::write_vtk_spheres(path.string(), broken), gpusolve::SizeMismatchError);
}

TEST_CASE("VTK fixed-geometry files hold boxes as hexahedra and planes as quads", "[scene_io]") {
  const auto path = temp_file("fixed.vtk");
  gpusolve::rbd::io::write_vtk_fixed(path.string(), sample_frame(), 5.0);
  const auto lines = lines_of(path);
  auto find = [&](const std::string& head) {
    for (std::size_t k = 0; k < lines.size(); ++k)
      if (lines[k].rfind(head, 0) == 0) return k;
    FAIL("missing " << head);
    return std::size_t{0};
  };
  CHECK(lines[3] == "DATASET UNSTRUCTURED_GRID");
  CHECK(lines[find("POINTS")] == "POINTS 16 float");  // 8 box corners + 2 x 4 plane corners
  CHECK(lines[find("CELLS")] == "CELLS 3 19");
  const auto types = find("CELL_TYPES");
  CHECK(lines[types + 1] == "12");
  CHECK(lines[types + 2] == "9");
  // The floor's corners lie on z = 0, 5 from the origin along both tangents.
  const auto floor0 = split(lines[find("POINTS") + 1 + 8], ' ');
  CHECK(std::stod(floor0[2]) == Approx(0.0).margin(1e-12));
  CHECK(std::fabs(std::stod(floor0[0])) == Approx(5.0));
}

TEST_CASE("POV-Ray scenes hold every object, camera and light", "[scene_io]") {
  const auto path = temp_file("frame.pov");
  gpusolve::rbd::io::write_povray(path.string(), sample_frame());
  const auto lines = lines_of(path);
  int spheres = 0, boxes = 0, planes = 0, cameras = 0, lights = 0;
  for (const auto& l : lines) {
    spheres += l.rfind("sphere {", 0) == 0;
    boxes += l.rfind("box {", 0) == 0;
    planes += l.rfind("plane {", 0) == 0;
    cameras += l.rfind("camera {", 0) == 0;
    lights += l.rfind("light_source {", 0) == 0;
  }
  CHECK(spheres == 3);
  CHECK(boxes == 1);
  CHECK(planes == 1);  // the ceiling would hide the scene from the camera above it
  CHECK(cameras == 1);
  CHECK(lights == 2);
  // y and z swap on the way to POV-Ray's y-up frame: sphere 0 at (0, 0, 1) is <0, 1, 0>.
  bool found = false;
  for (const auto& l : lines) found |= l.rfind("sphere { <0, 1, 0>, 1 ", 0) == 0;
  CHECK(found);
}

TEST_CASE("frames draw moving boxes and capsules at their orientation", "[scene_io]") {
  using namespace gpusolve::rbd;
  BodySet<double> set;
  set.add_plane({0, 0, 1}, 0);
  set.add_fixed_box({0, 0, -1}, {1, 1, 1});
  const double s = std::sqrt(0.5);
  set.add_box({3, 0, 1}, {1, 0.5, 0.25}, 1.0, {s, 0, 0, s});      // turned 90 degrees about z
  set.add_capsule({0, 3, 1}, 0.5, 2.0, 1.0, {s, 0, s, 0});        // its axis turned onto -z
  const Frame f = io::snapshot(set, 7, 0.5);
  REQUIRE(f.boxes.size() == 2);
  CHECK(!f.boxes[0].moving);
  CHECK(f.boxes[1].moving);
  REQUIRE(f.capsules.size() == 1);
  const auto ends = Frame::ends(f.capsules[0]);
  CHECK(ends[0][2] == Approx(3.0));  // 1 + 2 along +z for the -x end
  CHECK(ends[1][2] == Approx(-1.0));
  CHECK(ends[1][0] == Approx(0.0).margin(1e-12));

  const auto vtk = temp_file("shapes.vtk");
  io::write_vtk_shapes(vtk.string(), f);
  const auto lines = lines_of(vtk);
  auto line_after = [&](const std::string& head) {
    for (std::size_t k = 0; k < lines.size(); ++k)
      if (lines[k].rfind(head, 0) == 0) return k;
    FAIL("missing " << head);
    return std::size_t{0};
  };
  CHECK(lines[line_after("POINTS")] == "POINTS 10 float");  // 8 corners of the moving box, 2 capsule ends
  CHECK(lines[line_after("CELLS")] == "CELLS 2 12");
  const auto types = line_after("CELL_TYPES");
  CHECK(lines[types + 1] == "12");
  CHECK(lines[types + 2] == "3");
  // The moving box's first corner (-1, -0.5, -0.25) turned 90 degrees about z: (3.5, -1, 0.75).
  const auto corner = split(lines[line_after("POINTS") + 1], ' ');
  CHECK(std::stod(corner[0]) == Approx(3.5));
  CHECK(std::stod(corner[1]) == Approx(-1.0));
  CHECK(std::stod(corner[2]) == Approx(0.75));
  const auto fixed = temp_file("shapes_fixed.vtk");
  io::write_vtk_fixed(fixed.string(), f, 5.0);
  const auto fixed_lines = lines_of(fixed);
  CHECK(std::count(fixed_lines.begin(), fixed_lines.end(), std::string("POINTS 12 float")) == 1);  // the fixed box, the floor

  const auto pov = temp_file("shapes.pov");
  io::write_povray(pov.string(), f);
  int sweeps = 0, walls = 0, coloured = 0;
  for (const auto& l : lines_of(pov)) {
    sweeps += l.rfind("sphere_sweep {", 0) == 0;
    walls += l.rfind("box {", 0) == 0 && l.find("Wall") != std::string::npos;
    coloured += l.rfind("box {", 0) == 0 && l.find("texture { S") != std::string::npos;
  }
  CHECK(sweeps == 1);
  CHECK(walls == 1);
  CHECK(coloured == 1);
}
