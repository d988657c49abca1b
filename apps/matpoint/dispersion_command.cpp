// `matpoint dispersion`: dispersion table and Courant bounds of the linearised 1-D MPM of Gong 2015
// ch. 7, plus DIR/dispersion.csv, DIR/dispersion_bounds.csv and DIR/plots/dispersion_*.png.
#include "dispersion_command.hpp"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>
#include <numbers>
#include <sstream>
#include <vector>

#include "matpoint/analysis/dispersion.hpp"
#include "matpoint/core/errors.hpp"
#include "matpoint/core/subprocess.hpp"
#include "matpoint/io/atomic_file.hpp"

namespace matpoint {

namespace {

struct DispersionOptions {
  std::vector<int> particles_per_cell{1, 2, 3, 4};
  double courant = 0.5;
  std::string relation_name = "corrected";
  DispersionRelation relation = DispersionRelation::Corrected;  // set from relation_name
  int rows = 9;
  int samples = 181;
  std::string out_dir = "out";
  bool json = false;
  bool plots = true;
};

struct BoundRow {
  int particles_per_cell;
  CourantBound tight;  // Gong (7.29) with the square kept
  double sufficient;   // Gong (7.31)-(7.32) as printed
  double scheme;       // Bloch analysis of (7.15)-(7.16)
};

const char* relation_description(DispersionRelation relation) {
  return relation == DispersionRelation::Scheme
             ? "Bloch analysis of the scheme (7.15)-(7.16), M = CFL sin(theta/2)"
             : "eq. (7.29) with the square kept (the text drops it before (7.31))";
}

std::string curves_csv(const DispersionOptions& o) {
  std::ostringstream out;
  out.precision(12);
  out << "relation,particles_per_cell,courant,theta,m,spectral_radius,omega_dt,phase_speed_ratio,growth_per_"
         "step\n";
  for (const int n : o.particles_per_cell)
    for (const auto& p : dispersion_curve(o.courant, n, o.relation, o.samples))
      out << to_string(o.relation) << ',' << n << ',' << o.courant << ',' << p.theta << ',' << p.m << ','
          << p.spectral_radius << ',' << p.omega_dt << ',' << p.phase_speed_ratio << ',' << p.growth_per_step
          << '\n';
  return out.str();
}

std::string bounds_csv(const std::vector<BoundRow>& bounds) {
  std::ostringstream out;
  out.precision(12);
  out << "particles_per_cell,tight,theta_at_tight,sufficient,scheme\n";
  for (const auto& b : bounds)
    out << b.particles_per_cell << ',' << b.tight.courant << ',' << b.tight.theta << ',' << b.sufficient
        << ',' << b.scheme << '\n';
  return out.str();
}

/// "" when plots/dispersion_*.png were drawn, else why not.
std::string draw_dispersion_plots(const std::filesystem::path& out_dir,
                                  const std::filesystem::path& scripts_dir) {
  if (scripts_dir.empty()) return "no scripts folder";
  return run_python_script(scripts_dir / "plot_dispersion.py", {out_dir.string()});
}

void print_text(const DispersionOptions& o, const std::vector<BoundRow>& bounds) {
  std::printf("Linearised 1-D MPM dispersion, Gong 2015 ch. 7: %s\n", relation_description(o.relation));
  std::printf(
      "CFL = C F0 dt / h = %g; theta = k h; c_num/c = Re(omega) / (C F0 k); growth = ln max|lambda| per "
      "step\n",
      o.courant);
  for (const int n : o.particles_per_cell) {
    std::printf("\nN_p^e = %d\n  theta/pi         |M|  max|lambda|    c_num/c  growth/step\n", n);
    for (const auto& p : dispersion_curve(o.courant, n, o.relation, o.rows))
      std::printf("  %8.4f  %10.6f  %11.6f  %9.6f  %11.6f\n", p.theta / std::numbers::pi, std::fabs(p.m),
                  p.spectral_radius, p.phase_speed_ratio, p.growth_per_step);
  }
  std::printf(
      "\nCourant bounds: the largest CFL with max|lambda| <= 1 at every theta in [0, max(2, N) pi]\n");
  std::printf("  N_p^e  tight (7.29)  theta/pi  sufficient (7.32)  scheme (7.15-16)\n");
  for (const auto& b : bounds)
    std::printf("  %5d  %12.8f  %8.5f  %17.8f  %16.8f\n", b.particles_per_cell, b.tight.courant,
                b.tight.theta / std::numbers::pi, b.sufficient, b.scheme);
  std::printf(
      "tight: Gong (7.29) with the square kept; sufficient: (7.31)-(7.32) as printed; scheme: exact Bloch "
      "analysis\nof (7.15)-(7.16). The real FLIP loop is less stable (about 0.71-0.77): "
      "docs/theory/stability.md\n");
}

void print_json(const DispersionOptions& o, const std::vector<BoundRow>& bounds,
                const std::vector<std::string>& files) {
  nlohmann::json out;
  out["source"] = "Gong 2015 ch. 7; gong-2015-improving-mpm.md section 6";
  out["relation"] = to_string(o.relation);
  out["courant"] = o.courant;
  out["curves"] = nlohmann::json::array();
  for (const int n : o.particles_per_cell) {
    nlohmann::json rows = nlohmann::json::array();
    for (const auto& p : dispersion_curve(o.courant, n, o.relation, o.rows))
      rows.push_back({{"theta", p.theta},
                      {"m", p.m},
                      {"spectral_radius", p.spectral_radius},
                      {"omega_dt", p.omega_dt},
                      {"phase_speed_ratio", p.phase_speed_ratio},
                      {"growth_per_step", p.growth_per_step}});
    out["curves"].push_back({{"particles_per_cell", n}, {"rows", rows}});
  }
  out["bounds"] = nlohmann::json::array();
  for (const auto& b : bounds)
    out["bounds"].push_back({{"particles_per_cell", b.particles_per_cell},
                             {"tight", b.tight.courant},
                             {"theta_at_tight", b.tight.theta},
                             {"sufficient", b.sufficient},
                             {"scheme", b.scheme}});
  out["files"] = files;
  std::printf("%s\n", out.dump(2).c_str());
}

int run_dispersion(const DispersionOptions& o, const std::string& scripts_dir) {
  std::vector<BoundRow> bounds;
  for (const int n : o.particles_per_cell)
    bounds.push_back({n, tight_courant_bound(n, DispersionRelation::Corrected), sufficient_courant_bound(n),
                      tight_courant_bound(n, DispersionRelation::Scheme).courant});

  const std::filesystem::path out_dir = o.out_dir;
  std::filesystem::create_directories(out_dir);
  write_file_atomically(out_dir / "dispersion.csv", curves_csv(o));
  write_file_atomically(out_dir / "dispersion_bounds.csv", bounds_csv(bounds));
  std::vector<std::string> files{(out_dir / "dispersion.csv").string(),
                                 (out_dir / "dispersion_bounds.csv").string()};
  if (o.plots) {
    if (const auto error = draw_dispersion_plots(out_dir, scripts_dir); error.empty()) {
      for (const char* name : {"amplitude", "phase_speed", "growth"})
        files.push_back((out_dir / "plots" / (std::string("dispersion_") + name + ".png")).string());
    } else {
      std::fprintf(stderr, "warning: could not draw plots: %s\n", error.c_str());
    }
  }

  if (o.json) {
    print_json(o, bounds, files);
  } else {
    print_text(o, bounds);
    std::printf("\nwrote");
    for (const auto& f : files) std::printf(" %s", f.c_str());
    std::printf("\n");
  }
  return kExitOk;
}

}  // namespace

DispersionCommand add_dispersion_command(CLI::App& app, const std::string& scripts_dir) {
  auto options = std::make_shared<DispersionOptions>();
  auto* sub = app.add_subcommand("dispersion",
                                 "linearised 1-D stability/dispersion analysis (Gong 2015 ch. 7): table, "
                                 "Courant bounds, CSV and plots");
  sub->add_option("--particles-per-cell,-n", options->particles_per_cell,
                  "particles per cell N_p^e (one or more)")
      ->check(CLI::Range(1, 64))
      ->capture_default_str();
  sub->add_option("--courant", options->courant, "Courant number C F0 dt / h of the table and curves")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  sub->add_option("--relation", options->relation_name,
                  "corrected: Gong (7.29) with the square kept; scheme: Bloch analysis of (7.15)-(7.16)")
      ->check(CLI::IsMember({"corrected", "scheme"}))
      ->capture_default_str();
  sub->add_option("--rows", options->rows, "table rows per N_p^e, theta evenly spaced on [0, pi]")
      ->check(CLI::Range(2, 100000))
      ->capture_default_str();
  sub->add_option("--samples", options->samples, "CSV points per N_p^e on [0, pi]")
      ->check(CLI::Range(2, 1000000))
      ->capture_default_str();
  sub->add_option("--out", options->out_dir,
                  "output folder for dispersion.csv, dispersion_bounds.csv, plots/")
      ->capture_default_str();
  sub->add_flag("--json", options->json,
                "print JSON (curves at the table rows, bounds, files) instead of text");
  sub->add_flag("!--no-plots", options->plots, "do not draw plots/dispersion_*.png");
  return {sub, [options, scripts_dir] {
            options->relation = options->relation_name == "scheme" ? DispersionRelation::Scheme
                                                                   : DispersionRelation::Corrected;
            return run_dispersion(*options, scripts_dir);
          }};
}

}  // namespace matpoint
