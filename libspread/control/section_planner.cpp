#include "libspread/control/section_planner.hpp"

#include <algorithm>
#include <exception>
#include <string_view>

namespace spread::firmware {

SideGeometry side_geometry(double bout_width_m, int section_count) {
  SideGeometry g;
  g.side_sections = section_count / 2;
  g.section_width_m = section_count > 0 ? bout_width_m / section_count : 0.0;
  g.inner_m = section_count % 2 == 1 ? 0.5 * g.section_width_m : 0.0;
  return g;
}

SectionPlanner::SectionPlanner(SpreadPredictor& predictor, double max_beyond_percent, Threading threading)
    : predictor_(predictor), max_beyond_percent_(max_beyond_percent), threading_(threading) {
  if (threading_ == Threading::kWorker) worker_ = std::thread([this] { work(); });
}

SectionPlanner::~SectionPlanner() {
  {
    const std::lock_guard lock(mutex_);
    stop_ = true;
  }
  wake_.notify_all();
  if (worker_.joinable()) worker_.join();
}

SidePlan SectionPlanner::search(const SidePlanKey& key) {
  // A search that fails in any way (out of memory included) leaves the plan unknown: the ECU keeps the
  // field's setting for that side and reports its sections spread, never a dead planning thread.
  try {
    return search_unguarded(key);
  } catch (const std::exception&) {
    return SidePlan{};
  }
}

SidePlan SectionPlanner::search_unguarded(const SidePlanKey& key) {
  SidePlan plan;
  const std::string_view material(key.material.data());
  if (key.kind == PlanKind::kWind) {
    plan.known = predictor_.compensate_wind(material, key.rpm, key.bout_width_m, key.wind_x_m_s, key.wind_y_m_s,
                                            plan.wind_discs) == PredictionOutcome::kOk;
    return plan;
  }
  NarrowingRequest request;
  request.material = material;
  request.rpm = key.rpm;
  request.bout_width_m = key.bout_width_m;
  request.side = key.side;
  request.field_edge = key.kind == PlanKind::kFieldEdge;
  request.max_beyond_percent = max_beyond_percent_;
  request.wind_x_m_s = key.wind_x_m_s;
  request.wind_y_m_s = key.wind_y_m_s;
  // Every section of the side is rated: which of them the narrowed pass still spreads, inside the edge
  // line and beyond it.
  const SideGeometry g = side_geometry(key.bout_width_m, key.section_count);
  const auto count = static_cast<std::size_t>(std::clamp(g.side_sections, 0, kMaxSideSections));
  std::array<SideStrip, kMaxSideSections> strips{};
  for (std::size_t j = 0; j < count; ++j) {
    strips[j] = {g.edge_line_m(static_cast<int>(j)), g.edge_line_m(static_cast<int>(j) + 1)};
  }
  request.edge_line_m = key.kind == PlanKind::kSections ? g.edge_line_m(key.sections_on)
                                                        : 0.5 * key.bout_width_m - key.gap_m;
  const PredictionOutcome outcome =
      predictor_.narrow_side(request, std::span<const SideStrip>(strips.data(), count),
                             std::span<double>(plan.section_rate_percent.data(), count), plan.narrowing);
  plan.known = outcome == PredictionOutcome::kOk;
  return plan;
}

const SectionPlanner::Entry* SectionPlanner::find(const SidePlanKey& key) const {
  for (std::size_t i = 0; i < cache_count_; ++i) {
    if (cache_[i].key == key) return &cache_[i];
  }
  return nullptr;
}

void SectionPlanner::store(const SidePlanKey& key, const SidePlan& plan) {
  if (find(key) != nullptr) return;
  std::size_t slot = cache_count_;
  if (cache_count_ < kCacheSize) {
    ++cache_count_;
  } else {
    slot = static_cast<std::size_t>(
        std::min_element(cache_.begin(), cache_.end(), [](const Entry& a, const Entry& b) { return a.used < b.used; }) -
        cache_.begin());
  }
  cache_[slot] = Entry{key, plan, ++clock_};
}

void SectionPlanner::enqueue(const SidePlanKey& key, bool first) {
  if (find(key) != nullptr || (searching_ && *searching_ == key)) return;
  auto begin = queue_.begin(), end = queue_.begin() + static_cast<std::ptrdiff_t>(queue_count_);
  if (const auto at = std::find(begin, end, key); at != end) {
    if (first) std::rotate(begin, at, at + 1);  // asked for now: to the front
    return;
  }
  if (queue_count_ == kQueueCapacity) {
    if (!first) return;  // full of prepared keys: this one is prepared again when it is asked for
    --queue_count_;      // drop the last prepared key for the one asked for now
    end = queue_.begin() + static_cast<std::ptrdiff_t>(queue_count_);
  }
  if (first) {
    std::move_backward(begin, end, end + 1);
    queue_[0] = key;
  } else {
    queue_[queue_count_] = key;
  }
  ++queue_count_;
}

std::optional<SidePlan> SectionPlanner::lookup(const SidePlanKey& key) {
  {
    const std::lock_guard lock(mutex_);
    for (std::size_t i = 0; i < cache_count_; ++i) {
      if (cache_[i].key == key) {
        cache_[i].used = ++clock_;
        return cache_[i].plan;
      }
    }
    if (threading_ == Threading::kWorker) {
      enqueue(key, true);
      wake_.notify_one();
      return std::nullopt;
    }
  }
  const SidePlan plan = search(key);
  const std::lock_guard lock(mutex_);
  ++searches_;
  store(key, plan);
  return plan;
}

void SectionPlanner::prepare(const SidePlanKey& field) {
  if (threading_ == Threading::kInline) return;  // inline plans are made when asked for
  const SideGeometry g = side_geometry(field.bout_width_m, field.section_count);
  const std::lock_guard lock(mutex_);
  for (int sections_on = g.inner_m > 0.0 ? 0 : 1; sections_on < g.side_sections; ++sections_on) {
    for (const int side : {kLeftDisc, kRightDisc}) {
      SidePlanKey key = field;
      key.kind = PlanKind::kSections;
      key.side = side;
      key.sections_on = sections_on;
      enqueue(key, false);
    }
  }
  wake_.notify_one();
}

std::int64_t SectionPlanner::searches() const {
  const std::lock_guard lock(mutex_);
  return searches_;
}

void SectionPlanner::work() {
  std::unique_lock lock(mutex_);
  for (;;) {
    wake_.wait(lock, [this] { return stop_ || queue_count_ > 0; });
    if (stop_) return;
    const SidePlanKey key = queue_[0];
    std::move(queue_.begin() + 1, queue_.begin() + static_cast<std::ptrdiff_t>(queue_count_), queue_.begin());
    --queue_count_;
    searching_ = key;
    lock.unlock();
    const SidePlan plan = search(key);  // the long part, outside the lock
    lock.lock();
    ++searches_;
    store(key, plan);
    searching_.reset();
  }
}

}  // namespace spread::firmware
