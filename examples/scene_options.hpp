// Command-line options of gpusolve_scenes: one parser for every scene, with per-scene defaults.
#pragma once

#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace scenes {

// A command line the program cannot run: main prints the message and exits with 2.
struct UsageError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// What a scene runs with when the command line does not say otherwise.
struct SceneDefaults {
  long steps;
  long scale;  // number of spheres
  double dt;
  double tolerance;
  long max_iterations;
  long check_every;
  double friction;
};

// Everything the command line sets. Scene-dependent values are optional until
// resolved against the scene's defaults (resolve()).
struct Options {
  std::string scene;
  std::string backend = "auto";
  std::optional<long> steps, scale, max_iterations, check_every;
  std::optional<double> dt, tolerance, friction;
  double omega = 0;          // 0: the solver's default (Jacobi 0.5, Gauss-Seidel 1)
  std::string solver = "apgd";
  std::string friction_model = "cone";
  double margin = 0.1;       // contact distance: pairs closer than this take part in the solve
  long max_retries = 3;      // restarts of a diverging solve at half the omega
  double warm_start = 0.8;   // fraction of last step's impulse a persisting contact starts from
  std::string accumulation;  // empty: the solver's default strategy
  std::uint64_t seed = 1;
  std::string out;           // empty: out/<scene>
  long csv_every = 1;
  long frame_every = 0;      // 0: only the last step
  std::string frames = "vtk,pov";
  long status_every = 0;     // 0: about 20 lines per run when stderr is not a terminal
  bool quiet = false;
  bool help = false;

  void resolve(const SceneDefaults& d) {
    if (!steps) steps = d.steps;
    if (!scale) scale = d.scale;
    if (!dt) dt = d.dt;
    if (!tolerance) tolerance = d.tolerance;
    if (!max_iterations) max_iterations = d.max_iterations;
    if (!check_every) check_every = d.check_every;
    if (!friction) friction = d.friction;
    if (out.empty()) out = "out/" + scene;
    if (status_every == 0) status_every = std::max(1L, *steps / 20);
  }
  bool wants(const std::string& format) const {
    std::stringstream ss(frames);
    for (std::string f; std::getline(ss, f, ',');)
      if (f == format) return true;
    return false;
  }
};

inline const std::vector<std::string>& scene_names() {
  static const std::vector<std::string> names{"ballpark", "well", "hopper", "blocks"};
  return names;
}

// --help text. Scene defaults are listed per scene by the caller (defaults_text).
inline std::string usage(const std::string& accumulations, const std::string& defaults_text) {
  std::ostringstream o;
  o << "usage: gpusolve_scenes SCENE [options]     (or --scene SCENE)\n"
       "Runs one of the thesis's rigid-body scenes and writes statistics and frames.\n\n"
       "scenes:\n"
       "  ballpark   a block of 7x7x7 slightly misaligned spheres falling in a closed box\n"
       "  well       spheres poured into a round well of 150 fixed boxes standing on a plane\n"
       "  hopper     a square hopper filled with spheres; after a warm-up its outlet opens\n"
       "  blocks     boxes, capsules and spheres dropped onto a pyramid of boxes\n\n"
       "options (a value may follow '=' or come as the next argument):\n"
       "  --scene NAME          the scene, instead of the first positional argument\n"
       "  --backend B           cpu, gpu or auto (the GPU when this build and machine have one) [auto]\n"
       "  --steps N             time steps [scene]; the well's insertion stop (90%) and the\n"
       "                        hopper's warm-up (50%) scale with it\n"
       "  --scale N             number of spheres (blocks: of bodies dropped) [scene]\n"
       "  --dt X                time step in seconds [scene]\n"
       "  --solver NAME         jacobi (thesis 5.2), apgd (Nesterov-accelerated),\n"
       "                        gauss-seidel (coloured, parallel) or substepping (4 APGD\n"
       "                        substeps) [apgd]\n"
       "  --omega X             relaxation of the projected update, in [0, 2); 0: the solver's\n"
       "                        own (Jacobi 0.5, thesis: 0.2 to 0.7; APGD 0.3; Gauss-Seidel 1) [0]\n"
       "  --max-retries N       a diverging solve restarts from its start at half the omega,\n"
       "                        up to N times; 0 reports the divergence at once [3]\n"
       "  --warm-start X        a contact that persists starts its solve from X times its last\n"
       "                        impulse, in [0, 1]; 0 starts every solve from zero [0.8]\n"
       "  --margin X            pairs whose gap is below X (m) become contacts; a falling sphere\n"
       "                        moves up to ~0.07 per step here, so less lets it sink in first [0.1]\n"
       "  --tolerance X         residual at which the solver stops iterating [scene]\n"
       "  --max-iterations N    iterations per time step at most [scene]\n"
       "  --check-every N       residual checked every N iterations [scene]\n"
       "  --accumulation NAME   Jacobi: how contact updates are summed per body: "
    << accumulations
    << "\n"
       "  --friction MU         Coulomb friction coefficient; 0 selects the frictionless model [scene]\n"
       "  --friction-model M    cone (isotropic) or pyramid (thesis Eq. 7) [cone]\n"
       "  --seed N              seed of the random placement [1]\n"
       "  --out DIR             output folder [out/SCENE]\n"
       "  --csv-every N         a row of stats.csv every N steps [1]\n"
       "  --frame-every N       frames every N steps and at the last; 0: only the last [0]\n"
       "  --frames LIST         frame formats, comma-separated: vtk, pov, or none [vtk,pov]\n"
       "  --status-every N      status line every N steps when stderr is not a terminal [steps/20]\n"
       "  --quiet               no status line\n"
       "  --help                this text\n\n"
       "scene defaults:\n"
    << defaults_text
    << "\noutputs in DIR: stats.csv (one row per step), summary.json (parameters and totals),\n"
       "frame_NNNNN.vtk + fixed_NNNNN.vtk (ParaView), frame_NNNNN.pov (tools/render_povray.sh).\n"
       "exit status: 0 done, 1 failed (or the solver diverged), 2 bad command line.\n";
  return o.str();
}

namespace detail {

inline long parse_long(const std::string& opt, const std::string& s, long lo) {
  errno = 0;
  char* end = nullptr;
  const long v = std::strtol(s.c_str(), &end, 10);
  if (s.empty() || *end != '\0' || errno == ERANGE || v < lo)
    throw UsageError(opt + ": expected an integer >= " + std::to_string(lo) + ", got '" + s + "'");
  return v;
}

inline double parse_double(const std::string& opt, const std::string& s, double lo, bool open_lo) {
  errno = 0;
  char* end = nullptr;
  const double v = std::strtod(s.c_str(), &end);
  if (s.empty() || *end != '\0' || errno == ERANGE || !std::isfinite(v) || v < lo || (open_lo && v == lo)) {
    std::ostringstream m;
    m << opt << ": expected a number " << (open_lo ? "> " : ">= ") << lo << ", got '" << s << "'";
    throw UsageError(m.str());
  }
  return v;
}

inline std::string one_of(const std::string& opt, const std::string& s, const std::vector<std::string>& allowed) {
  for (const auto& a : allowed)
    if (s == a) return s;
  std::string list;
  for (const auto& a : allowed) list += (list.empty() ? "" : ", ") + a;
  throw UsageError(opt + ": '" + s + "' is not one of " + list);
}

}  // namespace detail

// Parses argv. `accumulations` are the strategy names the solver offers.
inline Options parse_options(int argc, const char* const* argv, const std::vector<std::string>& accumulations) {
  using namespace detail;
  Options o;
  std::vector<std::string> args(argv + 1, argv + argc);
  for (std::size_t i = 0; i < args.size(); ++i) {
    std::string a = args[i], value;
    bool has_value = false;
    if (a.rfind("--", 0) == 0 && a.find('=') != std::string::npos) {
      value = a.substr(a.find('=') + 1);
      a = a.substr(0, a.find('='));
      has_value = true;
    }
    auto next = [&]() -> std::string {
      if (has_value) return value;
      if (i + 1 >= args.size()) throw UsageError(a + ": missing value");
      return args[++i];
    };
    auto flag = [&] {
      if (has_value) throw UsageError(a + ": takes no value");
      return true;
    };
    if (a == "--help" || a == "-h") o.help = flag();
    else if (a == "--quiet" || a == "-q") o.quiet = flag();
    else if (a == "--scene") o.scene = one_of(a, next(), scene_names());
    else if (a == "--backend") o.backend = one_of(a, next(), {"cpu", "gpu", "auto"});
    else if (a == "--steps") o.steps = parse_long(a, next(), 1);
    else if (a == "--scale") o.scale = parse_long(a, next(), 1);
    else if (a == "--dt") o.dt = parse_double(a, next(), 0.0, true);
    else if (a == "--omega") {
      const std::string v = next();
      o.omega = parse_double(a, v, 0.0, false);
      if (o.omega >= 2.0) throw UsageError("--omega: must be in [0, 2), got '" + v + "'");
    }
    else if (a == "--max-retries") o.max_retries = parse_long(a, next(), 0);
    else if (a == "--warm-start") {
      const std::string v = next();
      o.warm_start = parse_double(a, v, 0.0, false);
      if (o.warm_start > 1.0) throw UsageError("--warm-start: must be in [0, 1], got '" + v + "'");
    }
    else if (a == "--margin") o.margin = parse_double(a, next(), 0.0, false);
    else if (a == "--tolerance") o.tolerance = parse_double(a, next(), 0.0, true);
    else if (a == "--max-iterations") o.max_iterations = parse_long(a, next(), 1);
    else if (a == "--check-every") o.check_every = parse_long(a, next(), 1);
    else if (a == "--accumulation") o.accumulation = one_of(a, next(), accumulations);
    else if (a == "--friction") o.friction = parse_double(a, next(), 0.0, false);
    else if (a == "--friction-model") o.friction_model = one_of(a, next(), {"cone", "pyramid"});
    else if (a == "--solver") o.solver = one_of(a, next(), {"gauss-seidel", "jacobi", "apgd", "substepping"});
    else if (a == "--seed") o.seed = static_cast<std::uint64_t>(parse_long(a, next(), 0));
    else if (a == "--out") {
      o.out = next();
      if (o.out.empty()) throw UsageError("--out: empty folder name");
    }
    else if (a == "--csv-every") o.csv_every = parse_long(a, next(), 1);
    else if (a == "--frame-every") o.frame_every = parse_long(a, next(), 0);
    else if (a == "--status-every") o.status_every = parse_long(a, next(), 1);
    else if (a == "--frames") {
      o.frames = next();
      std::stringstream ss(o.frames);
      for (std::string f; std::getline(ss, f, ',');) one_of(a, f, {"vtk", "pov", "none"});
    }
    else if (a.rfind("-", 0) == 0) throw UsageError("unknown option '" + a + "'");
    else if (o.scene.empty()) o.scene = one_of("scene", a, scene_names());
    else throw UsageError("unexpected argument '" + a + "' (the scene is already '" + o.scene + "')");
  }
  if (!o.help && o.scene.empty()) throw UsageError("no scene given: choose ballpark, well, hopper or blocks");
  return o;
}

}  // namespace scenes
