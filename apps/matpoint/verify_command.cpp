#include "verify_command.hpp"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include "matpoint/analysis/verification.hpp"
#include "matpoint/core/errors.hpp"
#include "matpoint/core/subprocess.hpp"

namespace matpoint {

namespace {

const std::map<std::string, ShapeKind> kShapes{
    {"linear", ShapeKind::Linear}, {"bspline2", ShapeKind::BSpline2}, {"bspline3", ShapeKind::BSpline3},
    {"ugimp", ShapeKind::UGIMP},   {"cpgimp", ShapeKind::CpGIMP},     {"cpdi1", ShapeKind::CPDI1},
    {"cpdi2", ShapeKind::CPDI2},   {"b2gimp", ShapeKind::B2GIMP},     {"b2cpdi", ShapeKind::B2CPDI}};

std::string slug(const std::string& name) {
  std::string s;
  for (char c : name)
    s += (std::isalnum(static_cast<unsigned char>(c)) != 0 || c == '.' || c == '-') ? c : '_';
  return s;
}

/// Writes DIR/plots/convergence_<case>.csv and draws the .png beside it with the project's script.
std::string write_plot(const VerificationOutcome& o, const std::filesystem::path& out,
                       const std::string& scripts) {
  const auto dir = out / "plots";
  std::filesystem::create_directories(dir);
  const auto csv = dir / ("convergence_" + slug(o.spec.name) + ".csv");
  std::ofstream f(csv);
  f << "h,cells,finished,displacement,stress,density,velocity,grid_velocity\n";
  for (const auto& r : o.runs)
    f << r.h << ',' << r.cells << ',' << (r.finished ? 1 : 0) << ',' << r.displacement << ',' << r.stress
      << ',' << r.density << ',' << r.velocity << ',' << r.grid_velocity << '\n';
  f.close();
  if (scripts.empty()) return "no scripts folder";
  return run_python_script(std::filesystem::path(scripts) / "plot_convergence.py",
                           {csv.string(), o.spec.name});
}

/// The pass rule of a check in words: ">= 1.8", "0.8 .. 1.2", "< 0.5 and not falling, or det F <= 0".
std::string pass_rule(const VerificationCheck& ch) {
  char text[96];
  if (ch.relation == ">=")
    std::snprintf(text, sizeof text, ">= %.2f", ch.expected - ch.tolerance);
  else if (ch.relation == "~")
    std::snprintf(text, sizeof text, "%.2f .. %.2f", ch.expected - ch.tolerance, ch.expected + ch.tolerance);
  else if (ch.relation == "no convergence")
    std::snprintf(text, sizeof text, "order < %.2f with finest error > coarsest / 2, or a det F <= 0 stop",
                  ch.expected);
  else
    std::snprintf(text, sizeof text, "%s %.4g", ch.relation.c_str(), ch.expected);
  return text;
}

}  // namespace

void VerifyCommand::add_to(CLI::App& app, std::string scripts_dir) {
  scripts_dir_ = std::move(scripts_dir);
  command_ = app.add_subcommand(
      "verify",
      "run built-in verification problems (Gong 2015 manufactured solutions) and report observed orders");
  command_->add_option("name", names_, "problems: mms-1d, mms-2d (default: the whole suite)");
  command_->add_option("--basis,--shape", shape_, "basis for the named problems (linear, bspline2, cpdi1, ...)");
  command_->add_option("--method", method_,
                       "mapping for the named problems: mpm (default), impm (Gong ch. 5, linear basis), "
                       "improved-cpdi (cpdi1 + MLS velocity, Gong §6.6)");
  command_->add_option("--amplitude", amplitude_, "G of the named problems (e.g. 1e-4 or 0.1)")
      ->check(CLI::PositiveNumber);
  command_->add_option("--cells", cells_, "resolutions: cells per direction (default 8 16 32 64)");
  command_->add_option("--ppc", particles_per_cell_, "particles per cell per direction")
      ->check(CLI::Range(1, 8))
      ->capture_default_str();
  command_->add_option("--out", out_, "folder for plots/convergence_*.png and .csv")->capture_default_str();
  command_->add_option("--threads", threads_, "OpenMP threads")->capture_default_str();
  command_->add_flag("--json", json_,
                     "print the checks as JSON: [{name, method, measured, expected, tolerance, pass}]");
  command_->add_flag("--full", full_, "the papers' resolutions (1-D down to h = 1/1024, 2-D to 1/64)");
  command_->add_flag("!--no-plots", plots_, "do not write plots");
  command_->add_flag(
      "!--nairn-walls", gong_walls_,
      "run every case with matpoint's default walls (solver.constrain_old_velocity = false: the "
      "FLIP increment keeps the wall reaction) instead of Gong's (Gong 2015 forms forces only at interior nodes)");
  command_->add_option("--time", time_,
                       "when the errors of the named problems are measured: T (one period, default) or T/4 "
                       "(stress is first order there: docs/verification.md, \"At T/4\")");
}

int VerifyCommand::run() const {
  std::vector<VerificationCase> cases;
  ShapeKind shape = ShapeKind::Linear;
  if (!shape_.empty()) {
    const auto it = kShapes.find(shape_);
    if (it == kShapes.end()) {
      std::fprintf(stderr,
                   "input error: --basis: got %s, expected one of linear, bspline2, bspline3, ugimp, cpgimp, "
                   "cpdi1, cpdi2, b2gimp, b2cpdi\n",
                   shape_.c_str());
      return kExitBadInput;
    }
    shape = it->second;
  }
  Mapping mapping = Mapping::MPM;
  if (method_ == "impm" || method_ == "improved-cpdi") {
    mapping = method_ == "impm" ? Mapping::IMPM : Mapping::MlsVelocity;
    const ShapeKind needed = method_ == "impm" ? ShapeKind::Linear : ShapeKind::CPDI1;
    if (!shape_.empty() && shape != needed) {
      std::fprintf(stderr, "input error: --basis: got %s, expected %s (or none) with --method %s\n",
                   shape_.c_str(), shape_name(needed), method_.c_str());
      return kExitBadInput;
    }
    shape = needed;
  } else if (!method_.empty() && method_ != "mpm") {
    std::fprintf(stderr, "input error: --method: got %s, expected one of mpm, impm, improved-cpdi\n",
                 method_.c_str());
    return kExitBadInput;
  }
  for (const auto& n : names_)
    if (n != "mms-1d" && n != "mms-2d") {
      std::fprintf(stderr, "input error: NAME: got %s, expected mms-1d or mms-2d\n", n.c_str());
      return kExitBadInput;
    }
  if (!time_.empty() && time_ != "T" && time_ != "T/4") {
    std::fprintf(stderr, "input error: --time: got %s, expected T or T/4\n", time_.c_str());
    return kExitBadInput;
  }
  const double end_time = time_ == "T/4" ? 0.005 : 0.02;  // one period T = 2 / c = 0.02 s
  const bool custom = !shape_.empty() || amplitude_ > 0 || !method_.empty() || !time_.empty();
  if (custom && names_.empty()) {
    std::fprintf(stderr, "input error: --shape/--method/--amplitude need a NAME (mms-1d or mms-2d)\n");
    return kExitBadInput;
  }
  if (custom) {
    for (const auto& n : names_)
      cases.push_back(
          make_case(n, shape, amplitude_ > 0 ? amplitude_ : 1e-4, full_, mapping, gong_walls_, end_time));
  } else {
    for (auto& c : verification_suite(full_))
      if (names_.empty() || std::find(names_.begin(), names_.end(), c.problem) != names_.end())
        cases.push_back(c);
  }
  for (auto& c : cases) {
    if (!cells_.empty()) c.cells = cells_;
    c.options.particles_per_cell = particles_per_cell_;
    c.options.threads = threads_;
    if (!gong_walls_ && c.options.constrain_old_velocity) {  // --nairn-walls: every case on the default
      c = make_case(c.problem, c.options.shape, c.options.amplitude, full_, c.options.mapping, false,
                    c.options.end_time);
      if (!cells_.empty()) c.cells = cells_;
      c.options.particles_per_cell = particles_per_cell_;
      c.options.threads = threads_;
    }
  }

  for (std::size_t i = 0; i < cases.size();
       ++i)  // --nairn-walls turns the suite's two wall variants into one
    for (std::size_t j = cases.size(); j-- > i + 1;)
      if (cases[j].name == cases[i].name) cases.erase(cases.begin() + static_cast<std::ptrdiff_t>(j));

  std::vector<VerificationOutcome> outcomes;
  bool all_pass = true, diverged = false;
  for (const auto& c : cases) {
    if (!json_)
      std::printf(
          "%s (%d-D, %s, G = %g, %d ppc, errors at t = %g, %s)\n  %-8s %-10s %-12s %-12s %-12s %-12s %-12s "
          "%s\n",
          c.name.c_str(), c.options.dim, method_name(c.options.shape, c.options.mapping).c_str(),
          c.options.amplitude, c.options.particles_per_cell, c.options.end_time,
          wall_treatment(c.options).c_str(), "h", "steps", "displacement", "stress", "density", "velocity",
          "grid vel.", "min J");
    std::fflush(stdout);
    auto outcome = run_case(c, [&](const MmsResult& r) {
      if (json_) return;
      std::printf("  1/%-6d %-10ld %-12.4e %-12.4e %-12.4e %-12.4e %-12.4e %.4f%s%s\n", r.cells, r.steps,
                  r.displacement, r.stress, r.density, r.velocity, r.grid_velocity, r.min_jacobian,
                  r.finished ? "" : "  DIVERGED: ", r.finished ? "" : r.message.c_str());
      std::fflush(stdout);
    });
    if (!json_) {
      std::printf("  order (least squares over the finished runs with h = 1/8 .. 1/64):");
      for (std::size_t k = 0; k < kMmsQuantities.size(); ++k)
        std::printf("  %s %.2f", kMmsQuantities[k], outcome.orders[k]);
      std::printf("\n");
      if (outcome.runs.size() > 2) {  // local orders between successive finished meshes
        std::printf("  local stress orders:");
        for (std::size_t k = 1; k < outcome.runs.size(); ++k) {
          const auto &a = outcome.runs[k - 1], &b = outcome.runs[k];
          if (a.finished && b.finished)
            std::printf(" %.2f", std::log(a.stress / b.stress) / std::log(a.h / b.h));
          else
            std::printf(" -");
        }
        std::printf("\n");
      }
      for (const auto& ch : outcome.checks)
        std::printf("  check %-4s %-40s measured %.3f, expected %s %.3f (pass %s)  [%s]\n",
                    ch.pass ? "PASS" : "FAIL", (ch.name.substr(ch.name.find(':') + 2)).c_str(), ch.measured,
                    ch.relation.c_str(), ch.expected, pass_rule(ch).c_str(), ch.source.c_str());
      if (outcome.checks.empty())
        std::printf("  (no threshold applies to this basis, amplitude and mesh range: report only)\n");
    }
    if (plots_)
      if (const auto error = write_plot(outcome, out_, scripts_dir_); !error.empty() && !json_)
        std::fprintf(stderr, "warning: could not draw %s/plots/convergence_%s.png: %s\n", out_.c_str(),
                     slug(c.name).c_str(), error.c_str());
    all_pass = all_pass && outcome.pass();
    // A run stopped by a guard (det F <= 0, NaN) is expected only where non-convergence is the claim.
    for (const auto& r : outcome.runs) {
      bool expected = false;  // a "does not converge" claim covers this mesh or a coarser one
      for (const auto& x : c.expectations)
        expected = expected || (x.claim == OrderClaim::NoConvergence && x.from_cells <= r.cells);
      diverged = diverged || (!r.finished && !expected);
    }
    outcomes.push_back(std::move(outcome));
  }
  // Extraction T14, T15: improved CPDI and IMPM against CPDI on the fine meshes (--full).
  const auto comparisons = comparison_checks(outcomes);
  for (const auto& ch : comparisons) {
    all_pass = all_pass && ch.pass;
    if (!json_)
      std::printf("check %-4s %s: %.4e < %.4e  [%s]\n", ch.pass ? "PASS" : "FAIL", ch.name.c_str(),
                  ch.measured, ch.expected, ch.source.c_str());
  }
  if (json_)
    std::printf("%s\n", checks_json(outcomes, comparisons).dump(2).c_str());
  else
    std::printf("%s\n", all_pass ? "all checks pass" : "SOME CHECKS FAIL");
  if (diverged) {
    if (!json_) std::printf("a run stopped on a numerical guard (det F <= 0 or NaN): exit 3\n");
    return kExitNumerical;
  }
  return all_pass ? kExitOk : kExitOther;
}

}  // namespace matpoint
