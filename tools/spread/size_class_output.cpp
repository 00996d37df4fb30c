#include "tools/spread/size_class_output.hpp"

#include <algorithm>
#include <cmath>
#include <iostream>
#include <map>
#include <sstream>

#include "libspread/analysis/plot/plot.hpp"
#include "tools/spread/error_exit.hpp"
#include "tools/spread/number_format.hpp"

namespace spread::cli {
// The helpers in a namespace of their own: the CLI's files compile together (tools/spread/CMakeLists.txt).
namespace size_class_output {
namespace {

using nlohmann::json;
using size_classes::ClassPattern;

json number_or_null(double v) { return std::isfinite(v) ? json(v) : json(nullptr); }

// "< 2.00 mm", "2.00-2.50 mm", ">= 5.00 mm".
std::string class_label(const ClassPattern& c) {
  if (c.lower_mm <= 0.0) return "< " + format("%.2f mm", c.upper_mm);
  if (!std::isfinite(c.upper_mm)) return ">= " + format("%.2f mm", c.lower_mm);
  return format("%.2f", c.lower_mm) + "-" + format("%.2f mm", c.upper_mm);
}

std::string cv_text(const ClassPattern& c) {
  if (c.sample_count == 0) return "none: no granules in this class";
  if (c.status != predict::PredictStatus::kOk) return std::string("no prediction (") + predict::to_string(c.status) + ")";
  std::string t = format("%.1f %%", 100.0 * c.cv_to_and_fro);
  if (std::isfinite(c.cv_to_and_fro_se)) t += format(" ± %.1f", 1.96 * 100.0 * c.cv_to_and_fro_se);
  return t + format(" to-and-fro, %.1f %% racetrack", 100.0 * c.cv_racetrack);
}

void print_class_line(const std::string& label, const ClassPattern& c) {
  std::cout << "    " << label << std::string(label.size() < 24 ? 24 - label.size() : 1, ' ')
            << format("%5.1f %%", 100.0 * c.mass_fraction) << format("  %6.0f samples", static_cast<double>(c.sample_count));
  if (c.status == predict::PredictStatus::kOk) std::cout << format("  R %.2f m", c.mean_radius_m);
  std::cout << "  CV " << cv_text(c) << "\n";
}

// The classes' trays side by side by tray centre (each class's layout is symmetric with the same tray
// width, so equal centres are the same tray), in % of the discharged mass; trays where no class has
// 0.05 % left out, and classes without a prediction.
void print_class_trays(const size_classes::SizeClassPatterns& p) {
  std::map<long, std::vector<double>> rows;  // centre in mm → per class
  double width_m = 0.0;
  for (std::size_t i = 0; i < p.classes.size(); ++i) {
    const ClassPattern& c = p.classes[i];
    if (c.tray_mass_fraction.empty()) continue;
    width_m = c.trays.tray_width_m;
    for (int k = 0; k < static_cast<int>(c.tray_mass_fraction.size()); ++k) {
      std::vector<double>& row = rows[std::lround(1e3 * c.trays.centre_m(k))];
      row.resize(p.classes.size(), 0.0);
      row[i] = c.tray_mass_fraction[static_cast<std::size_t>(k)];
    }
  }
  std::cout << "  pattern per size class (% of the discharged mass per " << format("%.2f m", width_m) << " tray):\n"
            << "    centre m";
  for (const ClassPattern& c : p.classes) {
    if (!c.tray_mass_fraction.empty()) std::cout << "  " << class_label(c);
  }
  std::cout << "\n";
  for (const auto& [centre_mm, row] : rows) {
    double most = 0.0;
    for (double v : row) most = std::max(most, v);
    if (most < 5e-4) continue;
    std::cout << format("    %8.2f", 1e-3 * static_cast<double>(centre_mm));
    for (std::size_t i = 0; i < row.size(); ++i) {
      if (p.classes[i].tray_mass_fraction.empty()) continue;  // a class without a prediction: no column
      const std::size_t w = class_label(p.classes[i]).size();
      const std::string v = format("%.2f", 100.0 * row[i]);
      std::cout << "  " << std::string(w > v.size() ? w - v.size() : 0, ' ') << v;
    }
    std::cout << "\n";
  }
}

// A class's trays on a wider layout of the same tray width: both even counts about the centre line, so
// the class's trays sit in the middle.
std::vector<double> on_layout(const ClassPattern& c, int tray_count) {
  std::vector<double> out(static_cast<std::size_t>(tray_count), 0.0);
  const auto offset = static_cast<std::size_t>((tray_count - c.trays.tray_count) / 2);
  for (std::size_t k = 0; k < c.tray_mass_fraction.size(); ++k) out[offset + k] = c.tray_mass_fraction[k];
  return out;
}

json class_json(const ClassPattern& c) {
  return {{"lower_mm", c.lower_mm},
          {"upper_mm", number_or_null(c.upper_mm)},
          {"mass_percent", 100.0 * c.mass_fraction},
          {"sample_count", c.sample_count},
          {"status", c.sample_count == 0 ? "no granules" : predict::to_string(c.status)},
          {"mean_radius_m", number_or_null(c.mean_radius_m)},
          {"cv_to_and_fro_percent", number_or_null(100.0 * c.cv_to_and_fro)},
          {"cv_to_and_fro_se_percent", number_or_null(100.0 * c.cv_to_and_fro_se)},
          {"cv_racetrack_percent", number_or_null(100.0 * c.cv_racetrack)},
          {"transverse", {{"tray_width_m", c.trays.tray_width_m},
                          {"left_edge_m", c.trays.left_edge_m()},
                          {"mass_fraction", c.tray_mass_fraction}}}};
}

}  // namespace
}  // namespace size_class_output

using namespace size_class_output;
using nlohmann::json;

std::vector<double> parse_size_class_boundaries_mm(const std::string& text) {
  std::vector<double> out;
  std::stringstream parts(text);
  for (std::string item; std::getline(parts, item, ',');) {
    char* end = nullptr;
    const double v = std::strtod(item.c_str(), &end);
    if (end == item.c_str() || *end != '\0' || !std::isfinite(v) || !(v > 0.0) || (!out.empty() && !(v > out.back())))
      throw BadInput("--size-class-mm: class boundaries in mm, > 0 and increasing, comma-separated; got '" + text + "'");
    out.push_back(v);
  }
  if (out.empty()) throw BadInput("--size-class-mm: at least one class boundary (mm)");
  return out;
}

void print_size_classes(const size_classes::SizeClassPatterns& p) {
  std::cout << "  granule sizes (the launch samples by mass): SGN " << format("%.0f", p.sizes.size_guide_number) << ", UI "
            << format("%.0f", p.sizes.uniformity_index) << " (d50 " << format("%.2f mm", p.sizes.d50_mm) << ")\n"
            << "  size classes at the " << format("%.2f m", p.bout_width_m)
            << " bout, each class alone (mass share, launch samples, mean landing radius R, CV):\n";
  for (const ClassPattern& c : p.classes) print_class_line(class_label(c), c);
  print_class_line("fine half " + class_label(p.fine), p.fine);
  print_class_line("coarse half " + class_label(p.coarse), p.coarse);
  print_class_trays(p);
}

void write_size_halves_png(const size_classes::SizeClassPatterns& p, const std::string& path) {
  if (p.fine.tray_mass_fraction.empty() || p.coarse.tray_mass_fraction.empty())
    throw BadInput("--size-class-png: the fine or the coarse half has no prediction");
  metrics::TrayLayout trays = p.fine.trays;
  trays.tray_count = std::max(p.fine.trays.tray_count, p.coarse.trays.tray_count);
  const std::vector<double> fine = on_layout(p.fine, trays.tray_count), coarse = on_layout(p.coarse, trays.tray_count);
  plot::TransverseOptions options;
  options.units = plot::MassUnits::kFraction;
  options.series_label = "fine half (< " + format("%.2f mm)", p.sizes.d50_mm);
  options.second_tray_mass_kg = coarse;
  options.second_label = "coarse half (>= " + format("%.2f mm)", p.sizes.d50_mm);
  options.bout_width_m = p.bout_width_m;
  plot::write_transverse_png(fine, trays, path,
                             "size segregation: SGN " + format("%.0f", p.sizes.size_guide_number) + ", UI " +
                                 format("%.0f", p.sizes.uniformity_index) + ", bout " + format("%.2f m", p.bout_width_m),
                             options);
}

json size_classes_json(const size_classes::SizeClassPatterns& p) {
  json classes = json::array();
  for (const ClassPattern& c : p.classes) classes.push_back(class_json(c));
  return {{"size_guide_number", p.sizes.size_guide_number},
          {"uniformity_index", p.sizes.uniformity_index},
          {"d50_mm", p.sizes.d50_mm},
          {"bout_width_m", p.bout_width_m},
          {"classes", classes},
          {"fine", class_json(p.fine)},
          {"coarse", class_json(p.coarse)}};
}

}  // namespace spread::cli
