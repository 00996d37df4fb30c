// `spread trajectory`: fly one granule from a launch state to the ground (libspread/physics/flight) and print
// where and when it lands. Exit 2 with a message naming the bad input for bad arguments.
#include <cmath>
#include <iostream>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "libspread/core/strict_number.hpp"
#include "libspread/physics/flight/flight.hpp"
#include "tools/spread/command_registry.hpp"

namespace spread::cli::cmd_trajectory {
namespace {

using spread::Vec3;
namespace flight = spread::flight;

struct TrajectoryOptions {
  double diameter_m = 0.0;
  double density_kg_m3 = 0.0;
  std::string position;
  std::string velocity;
  std::string spin;
  double ground_z_m = 0.0;
  std::string effects = effect::to_string(effect::kDefault & flight::kAllEffects);  // a scene's default flight effects
  double air_density_kg_m3 = flight::Air{}.density_kg_m3;
  double air_viscosity_pa_s = flight::Air{}.viscosity_pa_s;
  std::string wind;
  std::string scheme = "dopri5";
  double dt_s = flight::Settings{}.dt_s;
  double tolerance = flight::Settings{}.rel_tol;
  std::string lift = "smooth";
  bool json = false;
};

// "X,Y,Z" → exactly `count` finite numbers; throws std::invalid_argument naming the option.
std::vector<double> parse_components(const std::string& option, const std::string& text, std::size_t count) {
  std::vector<double> values;
  std::string_view bad;
  if (!parse_number_list(text, values, bad)) {
    throw std::invalid_argument(option + ": \"" + std::string(bad) + "\" is not a finite number (in \"" + text + "\")");
  }
  if (values.size() != count) {
    throw std::invalid_argument(option + ": expected " + std::to_string(count) +
                                " comma-separated numbers, got \"" + text + "\"");
  }
  return values;
}

Vec3 parse_vec3(const std::string& option, const std::string& text) {
  const auto v = parse_components(option, text, 3);
  return Vec3(v[0], v[1], v[2]);
}

nlohmann::json to_json(const Vec3& v) { return nlohmann::json::array({v.x(), v.y(), v.z()}); }

int run(const TrajectoryOptions& o) {
  flight::Granule granule{o.diameter_m, o.density_kg_m3};
  flight::State launch;
  launch.position_m = parse_vec3("--position", o.position);
  launch.velocity_m_s = parse_vec3("--velocity", o.velocity);
  launch.spin_rad_s = parse_vec3("--spin", o.spin);
  const flight::EffectSet effects = flight::parse_effects(o.effects);

  flight::Air air;
  air.density_kg_m3 = o.air_density_kg_m3;
  air.viscosity_pa_s = o.air_viscosity_pa_s;
  if (!o.wind.empty()) {
    if ((effects & flight::kWind) == 0) {
      throw std::invalid_argument("--wind given but \"wind\" is not in --effects (\"" + o.effects +
                                  "\"); add it to let the wind act");
    }
    const auto w = parse_components("--wind", o.wind, 2);
    air.wind_m_s = Vec3(w[0], w[1], 0.0);
  }

  flight::Settings settings;
  if (o.scheme == "rk4") {
    settings.scheme = flight::Scheme::kRk4;
  } else if (o.scheme == "dopri5") {
    settings.scheme = flight::Scheme::kDormandPrince45;
  } else {
    throw std::invalid_argument("--scheme: unknown scheme \"" + o.scheme + "\" (rk4 or dopri5)");
  }
  settings.dt_s = o.dt_s;
  settings.rel_tol = o.tolerance;
  settings.abs_tol = 0.1 * o.tolerance;  // the library default pairs rtol 1e-6 with atol 1e-7
  if (o.lift == "smooth") {
    settings.lift = flight::LiftModel::kSmoothSaturating;
  } else if (o.lift == "obd") {
    settings.lift = flight::LiftModel::kOesterleBuiDinh;
  } else if (o.lift == "obd-printed") {
    settings.lift = flight::LiftModel::kOesterleBuiDinhAsPrinted;
  } else {
    throw std::invalid_argument("--lift: unknown lift model \"" + o.lift + "\" (smooth, obd or obd-printed)");
  }

  const flight::Landing landing = flight::fly_to_ground(granule, launch, o.ground_z_m, air, effects, settings);

  if (o.json) {
    nlohmann::json out;
    out["landing_position"] = to_json(landing.state.position_m);
    out["landing_velocity"] = to_json(landing.state.velocity_m_s);
    out["landing_spin"] = to_json(landing.state.spin_rad_s);
    out["flight_time"] = landing.flight_time_s;
    out["steps"] = landing.steps;
    out["rejected_steps"] = landing.rejected_steps;
    out["landed"] = landing.landed;
    out["effects"] = spread::effect::names_in(effects);
    out["scheme"] = o.scheme;
    out["lift"] = o.lift;
    std::cout << out.dump(2) << "\n";
  } else {
    const Vec3& p = landing.state.position_m;
    std::cout.precision(6);
    std::cout << (landing.landed ? "landed" : "did NOT land (max time/steps reached)") << " at x " << p.x()
              << " m, y " << p.y() << " m, z " << p.z() << " m after " << landing.flight_time_s << " s ("
              << landing.steps << " steps, " << landing.rejected_steps << " rejected; " << o.scheme
              << ", effects " << (effects == 0 ? std::string("none") : flight::effects_to_string(effects)) << ")\n";
  }
  return landing.landed ? spread::cli::kExitOk : spread::cli::kExitFailure;
}

spread::cli::CommandRegistration registration{"trajectory", [](CLI::App& app, int& exit_code) {
  // Heap state: must outlive parsing (the setup lambda returns before the callback runs).
  auto options = std::make_shared<TrajectoryOptions>();
  auto* sub = app.add_subcommand("trajectory", "Fly one granule from a launch state to the ground");
  sub->add_option("--diameter", options->diameter_m, "Granule diameter (m)")->required();
  sub->add_option("--density", options->density_kg_m3, "Granule density (kg/m^3)")->required();
  sub->add_option("--position", options->position, "Launch position X,Y,Z (m)")->required();
  sub->add_option("--velocity", options->velocity, "Launch velocity VX,VY,VZ (m/s)")->required();
  sub->add_option("--spin", options->spin, "Launch spin WX,WY,WZ (rad/s)")->required();
  sub->add_option("--ground-z", options->ground_z_m, "Ground height (m)")->capture_default_str();
  sub->add_option("--effects", options->effects,
                  "Effects that run: " + spread::effect::to_string(spread::flight::kAllEffects) +
                      " (or none); gravity always acts")
      ->capture_default_str();
  sub->add_option("--air-density", options->air_density_kg_m3, "Air density (kg/m^3)")->capture_default_str();
  sub->add_option("--air-viscosity", options->air_viscosity_pa_s, "Air dynamic viscosity (Pa s)")
      ->capture_default_str();
  sub->add_option("--wind", options->wind, "Wind VX,VY (m/s); needs \"wind\" in --effects");
  sub->add_option("--scheme", options->scheme, "Integrator: rk4 or dopri5")->capture_default_str();
  sub->add_option("--dt", options->dt_s, "RK4 step / Dormand-Prince first trial step (s)")->capture_default_str();
  sub->add_option("--tolerance", options->tolerance, "Dormand-Prince relative tolerance (abs = 0.1 x rel)")
      ->capture_default_str();
  sub->add_option("--lift", options->lift, "Lift model: smooth, obd or obd-printed")->capture_default_str();
  sub->add_flag("--json", options->json, "Machine-readable output on stdout");
  sub->callback([options, &exit_code] { exit_code = run(*options); });
}};

}  // namespace
}  // namespace spread::cli::cmd_trajectory
