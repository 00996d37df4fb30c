// A blend's answer (libspread/analysis/blends): the checks that can fail on the physics and on the
// bookkeeping. Tables are built by lookup_builder's own sweep from scenes written here: the analytic source
// (fast, no granule interaction, the same feed points for every component) where the check is about
// flight and arithmetic, the DEM (the tiny test machine) where it is about the mixed stream.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "libspread/analysis/blends/blend_patterns.hpp"
#include "libspread/analysis/metrics/metrics.hpp"
#include "libspread/io/scene/scene.hpp"
#include "libspread/io/tables/table_reader.hpp"
#include "lookup_builder/table_build.hpp"
#include "tests/support/temp_path.hpp"

namespace spread::blends {
namespace {

using spread::testing::TempPath;

struct Component {
  std::string name;
  double density_kg_m3, diameter_mean_m, friction;
  double fraction, n_pct = 0, p2o5_pct = 0, k2o_pct = 0;
};

std::string component_text(const Component& c) {
  std::ostringstream t;
  t << "[[materials.components]]\nname = \"" << c.name << "\"\ndensity_kg_m3 = " << c.density_kg_m3
    << "\ndiameter_mean_m = " << c.diameter_mean_m << "\ndiameter_sd_m = 0.3e-3\nfriction_wall = " << c.friction
    << "\nfriction_particle = " << c.friction << "\nyoungs_modulus_pa = 5e6\nmass_fraction = " << c.fraction
    << "\nn_pct = " << c.n_pct << "\np2o5_pct = " << c.p2o5_pct << "\nk2o_pct = " << c.k2o_pct << "\n";
  return t.str();
}

// The analytic source on the bundled default machine's disc, drag only, still air.
std::string analytic_scene(const std::vector<Component>& components) {
  std::string text = R"toml(
[machine]
disc_radius_m = 0.29
disc_height_m = 0.8
disc_count = 2
disc_spacing_m = 0.8
cone_angle_rad = 0.157
vane_count = 2
vane_end_radius_m = 0.29
[inlet]
offset_m = 0.12
angle_rad = 2.285
[effects]
enabled = ["particle_contact", "wall_contact", "rotation", "drag"]
[sweep]
rpm = [600.0]
source = "analytic"
samples_per_run = 600
[[materials]]
name = "blend"
)toml";
  for (const Component& c : components) text += component_text(c);
  return text;
}

struct BuiltTable {
  TempPath file{"blend.sqlite"};
  tables::TableContents contents;
};

void build(const scene::Scene& scene, BuiltTable& out) {
  lookup::BuildOptions options;
  options.output_path = out.file.path();
  lookup::build_tables(scene, options);
  out.contents = tables::read_table_file(out.file.path());
}
void build(const std::string& scene_text, BuiltTable& out) { build(scene::parse_scene(scene_text, "blend_test.toml"), out); }

predict::PredictionRequest request_at(double rpm, double bout_width_m = 0.0) {
  predict::PredictionRequest r;
  r.material = "unused";  // blend_patterns sets each component's own
  r.rpm = rpm;
  r.bout_width_m = bout_width_m;
  return r;
}

// Newton's drag decelerates a granule by (3 C_d ρ_air / (4 ρ d)) v²: at the same launch state the denser
// and the larger one flies further. Components of one friction have the analytic source's same launches
// (only their diameters differ), so every pair of components orders by density and size, whatever the seed.
TEST(BlendPatterns, DenserAndLargerFlyFurtherInStillAir) {
  BuiltTable t;
  build(analytic_scene({{"light small", 1257, 2.6e-3, 0.5, 0.3}, {"middle", 1606, 3.2e-3, 0.5, 0.4},
                        {"dense large", 1937, 3.8e-3, 0.5, 0.3}}),
        t);
  predict::Predictor predictor(t.contents);
  const BlendPatterns b = blend_patterns(predictor, *t.contents.find_blend("blend"), request_at(600.0));
  ASSERT_EQ(b.status, predict::PredictStatus::kOk);
  ASSERT_EQ(b.components.size(), 3u);
  for (std::size_t i = 0; i < 3; ++i)
    for (std::size_t j = i + 1; j < 3; ++j)
      EXPECT_GT(b.components[j].mean_radius_m, b.components[i].mean_radius_m + 0.1)
          << b.components[j].name << " against " << b.components[i].name;
  EXPECT_GT(b.separation_index, 0.02);  // they land apart, so the shares vary across the bout
}

// A nutrient carried by one component alone is spread as that component is: its CV is the component's
// (the CV does not change with a constant factor). The blend's pattern is the components' added by mass,
// so it holds all the mass they hold. Where every component meets the target the widest common bout is
// the least of their first bands, and the component that limits it is the one whose band ends there.
TEST(BlendPatterns, NutrientsTotalAndTheLimitingComponentAddUp) {
  BuiltTable t;
  build(analytic_scene({{"urea", 1257, 3.0e-3, 0.4, 0.3, 46}, {"dap", 1606, 2.5e-3, 0.6, 0.4, 18, 46},
                        {"mop", 1937, 3.0e-3, 0.6, 0.3, 0, 0, 60}}),
        t);
  predict::Predictor predictor(t.contents);
  const BlendPatterns b = blend_patterns(predictor, *t.contents.find_blend("blend"), request_at(600.0, 12.0));
  ASSERT_EQ(b.status, predict::PredictStatus::kOk);
  EXPECT_EQ(b.bout_width_m, 12.0);
  const NutrientPattern& k2o = b.nutrients[2];
  ASSERT_TRUE(k2o.carried);
  EXPECT_NEAR(k2o.cv_to_and_fro, b.components[2].cv_to_and_fro, 1e-12);
  EXPECT_NEAR(k2o.cv_racetrack, b.components[2].cv_racetrack, 1e-12);
  ASSERT_TRUE(b.nutrients[0].carried);  // N from urea and DAP: between theirs, not either's
  EXPECT_NE(b.nutrients[0].cv_to_and_fro, b.components[0].cv_to_and_fro);
  double blend_mass = 0.0, components_mass = 0.0;
  for (double m : b.tray_mass_fraction) blend_mass += m;
  for (const ComponentPattern& c : b.components)
    for (double m : c.tray_mass_fraction) components_mass += m;
  EXPECT_NEAR(blend_mass, components_mass, 1e-12);
  EXPECT_GT(blend_mass, 0.95);
  // The widest common bout: at its whole-tray floor every component meets the target, at the next tray
  // the limiting one does not, and no wider whole-tray bout suits them all; no component alone goes less far.
  ASSERT_GE(b.limiting_component, 0);
  ASSERT_GT(b.widest_common_bout_m, 0.0);
  const auto cv = [&](const ComponentPattern& c, double w) {
    return metrics::cv_at_width(c.tray_mass_fraction, b.trays, w, metrics::Overlap::kToAndFro);
  };
  const double w = b.trays.tray_width_m;
  const double inside = std::floor(b.widest_common_bout_m / w) * w;
  for (const ComponentPattern& c : b.components) {
    EXPECT_LE(cv(c, inside), 0.15) << c.name;
    EXPECT_LE(b.widest_common_bout_m, c.widest_width_m + 1e-9) << c.name;
  }
  EXPECT_GT(cv(b.components[static_cast<std::size_t>(b.limiting_component)], inside + w), 0.15);
  for (double wider = inside + w; wider <= b.trays.tray_count * w; wider += w) {
    bool all = true;
    for (const ComponentPattern& c : b.components) all = all && cv(c, wider) <= 0.15;
    EXPECT_FALSE(all) << wider << " m suits every component";
  }
}

// Two identical components of the analytic source get the same launches: the same pattern, shares that do
// not vary (separation 0), and the blend spreads as the single product does.
TEST(BlendPatterns, IdenticalAnalyticComponentsDoNotSeparate) {
  BuiltTable t;
  build(analytic_scene({{"a", 1606, 3.2e-3, 0.5, 0.5}, {"b", 1606, 3.2e-3, 0.5, 0.5}}), t);
  predict::Predictor predictor(t.contents);
  const BlendPatterns b = blend_patterns(predictor, *t.contents.find_blend("blend"), request_at(600.0, 15.0));
  ASSERT_EQ(b.status, predict::PredictStatus::kOk);
  EXPECT_EQ(b.components[0].tray_mass_fraction, b.components[1].tray_mass_fraction);
  EXPECT_NEAR(b.separation_index, 0.0, 1e-12);
  EXPECT_NEAR(b.cv_to_and_fro, b.components[0].cv_to_and_fro, 1e-12);
}

// ---- the DEM: the tiny test machine (tests/tables/data/tiny_dem.toml), its urea and DAP as components ----

std::string text_of(const std::string& path) {
  std::ifstream in(path);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// The tiny machine with `blend_components` (the tiny scene's own material keys) as a blend "blend", a
// thin feed and a fixed simulated time (no early stop), building `materials` (the blend and/or the tiny
// scene's own materials) at 650 rpm.
scene::Scene tiny_scene(const std::string& blend_components, const std::string& materials, double mass_flow_kg_s) {
  std::string text = text_of(std::string(SPREAD_SOURCE_DIR) + "/tests/tables/data/tiny_dem.toml");
  text.insert(text.find("[simulate]"), "[[materials]]\nname = \"blend\"\n" + blend_components);
  return scene::parse_scene(text, "tiny_blend.toml",
                            {"sweep.materials=" + materials, "sweep.rpm=[650.0]", "inlet.mass_flow_kg_s=" + std::to_string(mass_flow_kg_s),
                             "numerics.duration_s=0.6", "sweep.convergence_tolerance=1e-12"});
}

std::string tiny_component(const std::string& name, double density_kg_m3, double friction, double fraction) {
  std::ostringstream t;
  t << "[[materials.components]]\nname = \"" << name << "\"\ndensity_kg_m3 = " << density_kg_m3
    << "\nfriction_wall = " << friction << "\nfriction_particle = " << friction
    << "\ndiameter_mean_m = 3.2e-3\ndiameter_sd_m = 0.6e-3\nyoungs_modulus_pa = 5e6\nmass_fraction = " << fraction << "\n";
  return t.str();
}

struct MeanAndSe {
  double mean = 0.0, se = 0.0;
};
bool agree(const MeanAndSe& a, const MeanAndSe& b, double z = 4.0) {
  return std::abs(a.mean - b.mean) <= z * std::hypot(a.se, b.se);
}

// Mean launch speed (per rim speed) of a row's samples and its standard error.
MeanAndSe launch_speed(const tables::TableContents& c, const std::string& material) {
  std::vector<double> v;
  for (const tables::Run& run : c.runs)
    if (run.material == material)
      for (const tables::LaunchSample& s : run.samples) v.push_back(std::sqrt(s.vx_norm * s.vx_norm + s.vy_norm * s.vy_norm + s.vz_norm * s.vz_norm));
  MeanAndSe out;
  if (v.size() < 2) return out;
  for (double x : v) out.mean += x / static_cast<double>(v.size());
  double ss = 0.0;
  for (double x : v) ss += (x - out.mean) * (x - out.mean);
  out.se = std::sqrt(ss / static_cast<double>(v.size() - 1) / static_cast<double>(v.size()));
  return out;
}

// Mass-weighted mean |x| of a prediction's landings (machine frame) and its delta-method standard error.
MeanAndSe landing_reach(predict::Predictor& predictor, const std::string& material) {
  predict::PredictionRequest r = request_at(650.0);
  r.material = material;
  predict::Prediction p;
  EXPECT_EQ(predictor.predict(r, p), predict::PredictStatus::kOk) << material;
  double m = 0.0, mx = 0.0;
  for (std::size_t i = 0; i < p.landing_x_m.size(); ++i) {
    if (!std::isfinite(p.landing_x_m[i])) continue;
    m += p.landing_mass_fraction[i];
    mx += p.landing_mass_fraction[i] * std::abs(p.landing_x_m[i]);
  }
  MeanAndSe out{mx / m, 0.0};
  double var = 0.0;
  for (std::size_t i = 0; i < p.landing_x_m.size(); ++i) {
    if (!std::isfinite(p.landing_x_m[i])) continue;
    const double d = p.landing_mass_fraction[i] * (std::abs(p.landing_x_m[i]) - out.mean);
    var += d * d;
  }
  // Both discs' landings are mirror images (not independent): the left disc's alone carry the information.
  out.se = std::sqrt(2.0 * var) / m;
  return out;
}

// A blend of two components identical to the tiny scene's urea: each component's launches and landings
// agree with the other's and with the single product's row, within 4 standard errors.
TEST(BlendPatternsDem, TwoIdenticalComponentsSpreadAsTheProduct) {
  BuiltTable t;
  build(tiny_scene(tiny_component("u1", 1257, 0.4, 0.5) + tiny_component("u2", 1257, 0.4, 0.5), "[\"blend\", \"Urea\"]", 0.03), t);
  predict::Predictor predictor(t.contents);
  const MeanAndSe u1 = landing_reach(predictor, "blend / u1"), u2 = landing_reach(predictor, "blend / u2"),
                  product = landing_reach(predictor, "Urea");
  EXPECT_TRUE(agree(u1, u2)) << u1.mean << " ± " << u1.se << " against " << u2.mean << " ± " << u2.se;
  EXPECT_TRUE(agree(u1, product)) << u1.mean << " ± " << u1.se << " against " << product.mean << " ± " << product.se;
  EXPECT_TRUE(agree(u2, product)) << u2.mean << " ± " << u2.se << " against " << product.mean << " ± " << product.se;
  EXPECT_TRUE(agree(launch_speed(t.contents, "blend / u1"), launch_speed(t.contents, "Urea")));
  EXPECT_GT(u1.se, 0.0);
  const BlendPatterns b = blend_patterns(predictor, *t.contents.find_blend("blend"), request_at(650.0, 12.0));
  ASSERT_EQ(b.status, predict::PredictStatus::kOk);
  EXPECT_LT(b.separation_index, 0.5);
}

// A dilute feed: granules hardly meet on the disc, so each component of a urea–DAP blend launches as the
// single product's row does (mean launch speed within 4 standard errors).
TEST(BlendPatternsDem, DiluteFeedComponentsLaunchAsTheSingleProducts) {
  BuiltTable t;
  build(tiny_scene(tiny_component("Urea", 1257, 0.4, 0.5) + tiny_component("DAP", 1606, 0.6, 0.5),
                   "[\"blend\", \"Urea\", \"DAP\"]", 0.01),
        t);
  for (const char* name : {"Urea", "DAP"}) {
    const MeanAndSe component = launch_speed(t.contents, std::string("blend / ") + name);
    const MeanAndSe product = launch_speed(t.contents, name);
    ASSERT_GT(component.se, 0.0) << name;
    EXPECT_TRUE(agree(component, product)) << name << ": " << component.mean << " ± " << component.se << " against "
                                           << product.mean << " ± " << product.se;
  }
}

}  // namespace
}  // namespace spread::blends
