#include "lookup_builder/table_build.hpp"

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdio>
#include <deque>
#include <exception>
#include <mutex>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <thread>

#include "libspread/tables/table_writer.hpp"
#include "lookup_builder/progress.hpp"
#include "lookup_builder/run_source.hpp"

namespace spread::lookup {
namespace {

tables::Machine table_machine(const scene::Machine& m) {
  tables::Machine out;
  out.name = m.name;
  out.disc_radius_m = m.disc_radius_m;
  out.disc_height_m = m.disc_height_m;
  out.disc_spacing_m = m.disc_spacing_m;
  out.disc_count = m.disc_count;
  out.vane_count = m.vane_count;
  out.cone_angle_rad = m.cone_angle_rad;
  out.rotation_sense = m.rotation_sense;
  return out;
}

std::string format_rpm(double rpm) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", rpm);
  return text;
}

// "812 samples (dem, converged at 0.25 s)" — the log line's summary of a run.
std::string run_detail(const tables::Run& run) {
  std::string detail = std::to_string(run.samples.size()) + " samples (" + run.source;
  const nlohmann::json stats = nlohmann::json::parse(run.stats_json, nullptr, false);
  if (stats.is_object() && stats.contains("stop") && stats.contains("simulated_s")) {
    char text[64];
    std::snprintf(text, sizeof text, ", %s at %.3g s simulated", stats["stop"].get<std::string>().c_str(),
                  stats["simulated_s"].get<double>());
    detail += text;
  }
  return detail + ")";
}

}  // namespace

std::string SweepJob::label() const { return material->name + " @ " + format_rpm(rpm) + " rpm"; }

std::vector<SweepJob> sweep_jobs(const scene::Scene& scene) {
  std::vector<SweepJob> jobs;
  for (const scene::Material* material : scene.sweep_materials()) {
    for (double rpm : scene.sweep_rpms()) {
      jobs.push_back({material, rpm, static_cast<int>(jobs.size())});
    }
  }
  return jobs;
}

struct SweepWriter::Impl {
  Impl(const std::string& path, std::ostream* out, bool terminal, int total)
      : writer(path), progress(out, terminal, total) {}
  tables::TableWriter writer;
  Progress progress;
  BuildSummary summary;
  bool rebuild = false;
};

SweepWriter::SweepWriter(const scene::Scene& scene, const BuildOptions& options) {
  const std::string path = options.output_path.empty() ? scene.sweep.output : options.output_path;
  const std::vector<SweepJob> all = sweep_jobs(scene);
  impl_ = std::make_unique<Impl>(path, options.progress, options.terminal, static_cast<int>(all.size()));
  impl_->summary.output_path = path;
  impl_->rebuild = options.rebuild;
  tables::TableWriter& writer = impl_->writer;
  writer.write_machine(table_machine(scene.machine));
  std::vector<tables::Material> rows;
  for (const scene::Material* m : scene.sweep_materials()) rows.push_back(*m);
  writer.write_materials(rows);
  writer.write_meta("machine_scene_hash", scene.hash());
  for (const SweepJob& job : all) {
    if (!options.rebuild && writer.has_run(job.material->name, job.rpm)) {
      ++impl_->summary.runs_skipped;
      impl_->progress.skipped(job.label());
      continue;
    }
    pending_.push_back(job);
  }
}

SweepWriter::~SweepWriter() = default;

void SweepWriter::started(const SweepJob& job) { impl_->progress.started(job.label()); }

void SweepWriter::finished(const SweepJob& job, const tables::Run& run, double seconds) {
  impl_->writer.write_run(run, impl_->rebuild);  // one transaction: a kill loses at most the run in progress
  ++impl_->summary.runs_written;
  impl_->progress.finished(job.label(), run_detail(run), seconds);
}

void SweepWriter::failed(const SweepJob& job, const std::string& message) {
  impl_->progress.failed(job.label(), message);
}

BuildSummary SweepWriter::finish() {
  impl_->progress.close();
  return impl_->summary;
}

BuildSummary build_tables(const scene::Scene& scene, const BuildOptions& options) {
  if (options.jobs < 1) throw std::invalid_argument("jobs must be >= 1, got " + std::to_string(options.jobs));
  const int threads_per_run = options.threads_per_run > 0 ? options.threads_per_run : (options.jobs > 1 ? 1 : 0);
  const RunSource source = make_run_source(scene, threads_per_run);  // refuses unavailable sources before any write
  SweepWriter writer(scene, options);
  const std::vector<SweepJob>& pending = writer.pending();
  using Clock = std::chrono::steady_clock;

  if (options.jobs == 1 || pending.size() <= 1) {
    for (const SweepJob& job : pending) {
      writer.started(job);
      const auto start = Clock::now();
      tables::Run run;
      try {
        run = source(*job.material, job.rpm);
      } catch (const std::exception& e) {
        writer.failed(job, e.what());
        writer.finish();
        throw;
      }
      writer.finished(job, run, std::chrono::duration<double>(Clock::now() - start).count());
    }
    return writer.finish();
  }

  // Threads compute, this thread writes (SQLite has one writer): finished runs are handed over in a
  // queue and written in the order they finish. A failed run stops new runs from starting; the ones
  // already finished are still written.
  struct Done {
    const SweepJob* job;
    tables::Run run;
    double seconds;
  };
  std::mutex mutex;
  std::condition_variable ready;
  std::deque<Done> queue;
  std::atomic<std::size_t> next{0};
  std::atomic<bool> stop{false};
  std::exception_ptr error;
  const SweepJob* error_job = nullptr;
  int workers_running = std::min(options.jobs, static_cast<int>(pending.size()));
  std::vector<std::thread> workers;
  for (int w = 0, n = workers_running; w < n; ++w) {
    workers.emplace_back([&] {
      for (std::size_t i; !stop && (i = next++) < pending.size();) {
        writer.started(pending[i]);
        const auto start = Clock::now();
        try {
          tables::Run run = source(*pending[i].material, pending[i].rpm);
          const double seconds = std::chrono::duration<double>(Clock::now() - start).count();
          std::lock_guard lock(mutex);
          queue.push_back({&pending[i], std::move(run), seconds});
        } catch (...) {
          std::lock_guard lock(mutex);
          if (!error) {
            error = std::current_exception();
            error_job = &pending[i];
          }
          stop = true;
        }
        ready.notify_one();
      }
      std::lock_guard lock(mutex);
      --workers_running;
      ready.notify_one();
    });
  }
  std::exception_ptr write_error;
  for (;;) {
    std::unique_lock lock(mutex);
    ready.wait(lock, [&] { return !queue.empty() || workers_running == 0; });
    if (queue.empty()) break;
    Done done = std::move(queue.front());
    queue.pop_front();
    lock.unlock();
    if (write_error) continue;
    try {
      writer.finished(*done.job, done.run, done.seconds);
    } catch (...) {
      write_error = std::current_exception();
      stop = true;
    }
  }
  for (std::thread& t : workers) t.join();
  if (error) {
    try {
      std::rethrow_exception(error);
    } catch (const std::exception& e) {
      writer.failed(*error_job, e.what());
    } catch (...) {
    }
    writer.finish();
    std::rethrow_exception(error);
  }
  if (write_error) {
    writer.finish();
    std::rethrow_exception(write_error);
  }
  return writer.finish();
}

}  // namespace spread::lookup
