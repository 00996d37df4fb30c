#include "lookup_builder/table_build.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <cstring>
#include <chrono>
#include <condition_variable>
#include <cstdio>
#include <deque>
#include <exception>
#include <mutex>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <thread>

#include "libspread/analysis/predict/predictor.hpp"
#include "libspread/io/tables/table_reader.hpp"
#include "libspread/io/tables/table_writer.hpp"
#include "libspread/io/tables/machine_schema.hpp"
#include "libspread/io/tables/writer_lock.hpp"
#include "lookup_builder/progress.hpp"
#include "lookup_builder/run_source.hpp"

namespace spread::lookup {
namespace {

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

namespace {

std::string show(double value) {
  char text[40];
  std::snprintf(text, sizeof text, "%.9g", value);
  return text;
}

// Where the file's machine row and this scene's machine differ, as "machine.<field>: file X, scene Y".
void machine_differences(const tables::Machine& file, const tables::Machine& scene, std::vector<std::string>& out) {
  for (const tables::MachineColumn& c : tables::kMachineColumns) {
    const std::string field = "machine." + std::string(c.name);
    switch (c.kind) {
      case tables::MachineColumn::Kind::kText:
        if (file.*c.text != scene.*c.text) out.push_back(field + ": file \"" + file.*c.text + "\", scene \"" + scene.*c.text + "\"");
        break;
      case tables::MachineColumn::Kind::kReal:
        if (file.*c.real != scene.*c.real) out.push_back(field + ": file " + show(file.*c.real) + ", scene " + show(scene.*c.real));
        break;
      case tables::MachineColumn::Kind::kInteger:
        if (file.*c.integer != scene.*c.integer) {
          out.push_back(field + ": file " + std::to_string(file.*c.integer) + ", scene " + std::to_string(scene.*c.integer));
        }
        break;
    }
  }
}

void material_differences(const tables::Material& file, const tables::Material& scene, std::vector<std::string>& out) {
  const std::string at = "materials." + file.name + ".";
  const std::pair<const char*, std::pair<double, double>> fields[] = {
      {"density_kg_m3", {file.density_kg_m3, scene.density_kg_m3}},
      {"diameter_mean_m", {file.diameter_mean_m, scene.diameter_mean_m}},
      {"diameter_sd_m", {file.diameter_sd_m, scene.diameter_sd_m}},
      {"friction_wall", {file.friction_wall, scene.friction_wall}},
      {"friction_particle", {file.friction_particle, scene.friction_particle}},
      {"restitution", {file.restitution, scene.restitution}},
      {"youngs_modulus_pa", {file.youngs_modulus_pa, scene.youngs_modulus_pa}},
      {"poisson_ratio", {file.poisson_ratio, scene.poisson_ratio}},
      {"rolling_friction", {file.rolling_friction, scene.rolling_friction}}};
  for (const auto& [field, values] : fields) {
    if (values.first != values.second) {
      out.push_back(at + field + ": file " + show(values.first) + ", scene " + show(values.second));
    }
  }
}

// The `materials` rows of the sweep: each material's own, each blend's components' (named
// blend_component_name). A blend has no row of its own: `blend_components` holds it.
std::vector<tables::Material> material_rows(const scene::Scene& scene) {
  std::vector<tables::Material> rows;
  for (const scene::Material* m : scene.sweep_materials()) {
    if (!m->is_blend()) rows.push_back(*m);
    for (const tables::BlendComponent& c : m->components) {
      rows.push_back(c.material);
      rows.back().name = tables::blend_component_name(m->name, c.material.name);
    }
  }
  return rows;
}

tables::Blend blend_row(const scene::Material& blend) {
  tables::Blend row{blend.name, {}};
  for (const tables::BlendComponent& c : blend.components) {
    row.components.push_back({tables::blend_component_name(blend.name, c.material.name), c.mass_fraction, c.n_pct,
                              c.p2o5_pct, c.k2o_pct});
  }
  return row;
}

// Whether the file holds the job's runs: its material's, or every component row of its blend.
bool has_job_runs(tables::TableWriter& writer, const SweepJob& job) {
  if (!job.material->is_blend()) return writer.has_run(job.material->name, job.rpm);
  for (const tables::BlendComponent& c : job.material->components) {
    if (!writer.has_run(tables::blend_component_name(job.material->name, c.material.name), job.rpm)) return false;
  }
  return true;
}

// The scene's material a table row stands for, with the row's values: the material itself, or, for a
// blend component's row, the blend (whose inputs its runs carry) and the component's values.
struct RowOwner {
  const scene::Material* owner = nullptr;  // nullptr: a row of another scene
  tables::Material values;
};
RowOwner row_owner(const scene::Scene& scene, const std::string& row) {
  if (const scene::Material* m = scene.find_material(row); m != nullptr && !m->is_blend()) return {m, *m};
  for (const scene::Material& m : scene.materials) {
    for (const tables::BlendComponent& c : m.components) {
      if (tables::blend_component_name(m.name, c.material.name) != row) continue;
      RowOwner owner{&m, c.material};
      owner.values.name = row;
      return owner;
    }
  }
  return {};
}

// Everything in the file that this scene would have written differently: the machine, a material that
// has runs, or a run (of a material the scene describes) whose source or inputs differ. Runs of
// materials the scene does not describe are other scenes' rows of the same machine and stay.
std::vector<std::string> table_conflicts(tables::TableWriter& writer, const scene::Scene& scene) {
  std::vector<std::string> out;
  const std::optional<tables::Machine> machine = writer.stored_machine();
  if (machine) machine_differences(*machine, scene::table_machine(scene.machine), out);
  const std::vector<tables::TableWriter::StoredRun> runs = writer.stored_runs();
  for (const tables::Material& stored : writer.stored_materials()) {
    const RowOwner mine = row_owner(scene, stored.name);
    const bool has_runs = std::any_of(runs.begin(), runs.end(), [&](const auto& r) { return r.material == stored.name; });
    if (mine.owner != nullptr && has_runs) material_differences(stored, mine.values, out);
  }
  const std::string source = scene::to_string(scene.sweep.source);
  for (const auto& run : runs) {
    const scene::Material* mine = row_owner(scene, run.material).owner;
    if (mine == nullptr) continue;
    const std::string label = "run " + run.material + " @ " + format_rpm(run.rpm) + " rpm";
    if (run.source != source) {
      out.push_back(label + ": source " + run.source + " in the file, " + source + " in the scene");
    } else if (!scene.same_run_inputs(run.inputs_hash, *mine, run.rpm)) {
      out.push_back(label + ": built from other inputs (numerics, sweep or effects differ; inputs hash " +
                    (run.inputs_hash.empty() ? std::string("not recorded") : run.inputs_hash) + " in the file, " +
                    scene.run_inputs_hash(*mine, run.rpm) + " from the scene)");
    }
  }
  return out;
}

// Where a build writes: beside the table it makes. The table itself changes only by a rename of this file
// over it (rename(2) is atomic on POSIX file systems), so a reader opens either the previous complete
// table or the new one, never a file in mid-transaction, whatever moment a build is killed at. A killed
// build's staging file keeps its finished runs, and the next build of the same table resumes from it.
std::string staging_path_of(const std::string& path) { return path + ".building"; }

// What the staging file was copied from: the table's device, inode, size and modification time, or
// "absent". A staging file is resumed only while the table is still the one it was copied from.
constexpr const char* kStagingBaseKey = "staging_base";

std::string file_identity(const std::string& path) {
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0 || st.st_size == 0) return "absent";
  return std::to_string(st.st_dev) + ":" + std::to_string(st.st_ino) + ":" + std::to_string(st.st_size) + ":" +
         std::to_string(st.st_mtim.tv_sec) + "." + std::to_string(st.st_mtim.tv_nsec);
}

// The table's new state made durable before and after it takes the table's name (a crash right after the
// rename must not leave a name pointing at unwritten data): the file's data, then the directory entry.
void sync_path(const std::string& path, int flags) {
  const int fd = ::open(path.c_str(), flags | O_CLOEXEC);
  if (fd < 0) return;
  ::fsync(fd);
  ::close(fd);
}

// The predictor's landing grids and quantile cells (libspread/io/tables/landing_data.hpp) of every
// material whose stored landing data is missing or stale, derived from the file's rows as a reader would
// derive them and stored beside them, so that opening the table reads them instead of flying them. True
// when anything was written.
bool store_landing_data(tables::TableWriter& writer) {
  tables::TableContents contents;
  try {
    contents = tables::read_table_file(writer.path());
  } catch (const tables::TableError& e) {
    if (e.kind() == tables::TableErrorKind::kEmpty) return false;  // no runs: nothing to derive
    throw;
  }
  const predict::Predictor predictor(std::move(contents));
  const std::vector<tables::LandingData> derived = predictor.derived_landing_data();
  for (const tables::LandingData& landing : derived) writer.write_landing_data(landing);
  return !derived.empty();
}

}  // namespace

struct SweepWriter::Impl {
  Impl(std::ostream* out, bool terminal, int total) : progress(out, terminal, total) {}
  // The table's own writer lock, held for the build of a table that exists: a second builder (or any
  // TableWriter) of the same table is refused, and nothing writes the table while this build replaces it.
  // A fresh build takes none: the lock would create the file, and a build killed before its rename would
  // leave that empty file at the table's path. Its staging file's lock (the TableWriter's, beside the path)
  // keeps a second fresh build of the same path out, and the table's first state is the renamed staging
  // file, still locked by this build's writer.
  std::optional<tables::WriterLock> table_lock;
  bool fresh = false;  // no table at the path when the build began
  std::optional<tables::TableWriter> writer;  // on the staging file
  std::string staging_path;
  Progress progress;
  BuildSummary summary;
  bool rebuild = false;
  bool changed = false;          // the staging file differs from the table (runs written, rebuilt, resumed)
  std::size_t pending_done = 0;  // pending runs written (or found already written)
  std::string scene_hash;
};

SweepWriter::SweepWriter(const scene::Scene& scene, const BuildOptions& options) {
  const std::string path = options.output_path.empty() ? scene.sweep.output : options.output_path;
  const std::vector<SweepJob> all = sweep_jobs(scene);
  impl_ = std::make_unique<Impl>(options.progress, options.terminal, static_cast<int>(all.size()));
  impl_->summary.output_path = path;
  impl_->rebuild = options.rebuild;
  impl_->scene_hash = scene.hash();
  impl_->staging_path = staging_path_of(path);
  // The table as it is, checked before anything is written: ours, of this version, whole (a table left
  // with a rollback journal by an older builder is rolled back here), and no other writer on it.
  const bool table_exists = file_identity(path) != "absent";
  if (table_exists) {
    { tables::TableWriter check(path); }  // closed (its lock released) before the build's own lock
    impl_->table_lock.emplace(path);
  }
  impl_->fresh = !table_exists;
  impl_->writer.emplace(impl_->staging_path);
  tables::TableWriter& writer = *impl_->writer;
  const std::string base = file_identity(path);
  const std::optional<std::string> staged_base = writer.stored_meta(kStagingBaseKey);
  if (staged_base && *staged_base == base) {
    impl_->changed = true;
    if (options.progress != nullptr) {
      *options.progress << "lookup_builder: " << path << ": resuming the build interrupted in "
                        << impl_->staging_path << "\n";
    }
  } else if (table_exists) {
    writer.copy_from(path);
  } else {
    writer.clear();
  }
  writer.write_meta(kStagingBaseKey, base);
  const std::vector<std::string> conflicts = table_conflicts(writer, scene);
  if (!conflicts.empty()) {
    if (!options.rebuild) {
      std::string message = path + ": the file was built from another scene; refusing to mix its rows with this one "
                                   "(the file is unchanged):";
      const std::size_t shown = std::min<std::size_t>(conflicts.size(), 8);
      for (std::size_t i = 0; i < shown; ++i) message += "\n  " + conflicts[i];
      if (conflicts.size() > shown) message += "\n  ... and " + std::to_string(conflicts.size() - shown) + " more";
      message += "\nwrite to a new file (--output), or pass --rebuild to replace this table once the new one is complete";
      impl_->writer.reset();
      std::remove(impl_->staging_path.c_str());
      throw BuildConflictError(message);
    }
    // Rebuilt from scratch in the staging file; the old table is replaced only when the new one is complete.
    writer.clear();
    writer.write_meta(kStagingBaseKey, base);
    impl_->changed = true;
  }
  if (options.rebuild) impl_->changed = true;
  writer.write_machine(scene::table_machine(scene.machine));
  // The drop-point turns the scene states as checked against DEM rows: what the searches may use.
  const std::string validated_turn = tables::drop_point_turn_validated_text(scene.inlet.validated_turn_deg);
  if (writer.stored_meta(tables::kDropPointTurnValidatedKey) != validated_turn) {
    writer.write_meta(tables::kDropPointTurnValidatedKey, validated_turn);
    impl_->changed = true;
  }
  writer.write_materials(material_rows(scene));
  for (const scene::Material* m : scene.sweep_materials()) {
    if (m->is_blend()) writer.write_blend(blend_row(*m));
  }
  for (const SweepJob& job : all) {
    if (!options.rebuild && has_job_runs(writer, job)) {
      ++impl_->summary.runs_skipped;
      impl_->progress.skipped(job.label());
      continue;
    }
    pending_.push_back(job);
  }
  if (!pending_.empty()) impl_->changed = true;
  if (writer.stored_meta("machine_scene_hash") != impl_->scene_hash) impl_->changed = true;
}

SweepWriter::~SweepWriter() = default;

void SweepWriter::started(const SweepJob& job) { impl_->progress.started(job.label()); }

void SweepWriter::finished(const SweepJob& job, const std::vector<tables::Run>& runs, const RunCost& cost) {
  std::size_t samples = 0;
  int written = 0;
  // One transaction per run: a kill loses at most the run in progress (of a blend, the job is redone
  // while any of its component rows is missing, and the rows already stored are kept).
  for (const tables::Run& run : runs) {
    try {
      impl_->writer->write_run(run, impl_->rebuild);
    } catch (const tables::RunExistsError&) {
      continue;  // written meanwhile by an earlier, interrupted build of the same inputs: keep the stored run
    }
    samples += run.samples.size();
    ++written;
  }
  ++impl_->pending_done;
  if (written == 0) {
    ++impl_->summary.runs_skipped;
    impl_->progress.skipped(job.label());
    return;
  }
  impl_->summary.runs_written += written;
  const std::string detail = runs.size() == 1 ? run_detail(runs.front())
                                              : std::to_string(runs.size()) + " component rows, " + run_detail(runs.front());
  impl_->progress.finished(job.label(), detail, cost.wall_s, cost.cpu_s, cpu_s_per_1000_launches(cost, samples));
}

void SweepWriter::failed(const SweepJob& job, const std::string& message) {
  impl_->progress.failed(job.label(), message);
}

BuildSummary SweepWriter::finish() {
  impl_->progress.close();
  if (!impl_->writer) return impl_->summary;  // already finished
  tables::TableWriter& writer = *impl_->writer;
  // Every table this build leaves lists its runs with the list's checksum, also one it extends that was
  // written before the list was checked (its rows were each checked by their own checksums when copied).
  if (writer.list_runs()) impl_->changed = true;
  // The scene that completed this file; a failed build keeps the previous value (its finished runs are
  // kept all the same).
  if (impl_->pending_done == pending_.size()) {
    writer.write_meta("machine_scene_hash", impl_->scene_hash);
    if (store_landing_data(writer)) impl_->changed = true;
  }
  const std::string& path = impl_->summary.output_path;
  if (!impl_->changed) {
    // Nothing to do: the table stays byte-identical and the staging copy goes.
    impl_->writer.reset();
    std::remove(impl_->staging_path.c_str());
    return impl_->summary;
  }
  // A fresh build holds no lock on the path: a table that appeared there meanwhile (written by another
  // program) is not replaced; this build's table stays in its staging file.
  if (impl_->fresh && file_identity(path) != "absent") {
    throw tables::TableError(tables::TableErrorKind::kIo,
                             path + ": a table appeared there during this build; it is left as it is and the new table "
                                    "stays in " + impl_->staging_path);
  }
  writer.erase_meta(kStagingBaseKey);
  sync_path(impl_->staging_path, O_RDONLY);
  if (std::rename(impl_->staging_path.c_str(), path.c_str()) != 0) {
    throw tables::TableError(tables::TableErrorKind::kIo,
                             path + ": cannot replace it with the new table " + impl_->staging_path + ": " + std::strerror(errno));
  }
  const std::size_t slash = path.rfind('/');
  sync_path(slash == std::string::npos ? "." : (slash == 0 ? "/" : path.substr(0, slash)), O_RDONLY | O_DIRECTORY);
  impl_->writer.reset();  // after the rename: no other builder can take the staging name in between
  impl_->table_lock.reset();
  return impl_->summary;
}

BuildSummary build_tables(const scene::Scene& scene, const BuildOptions& options) {
  if (options.jobs < 1) throw std::invalid_argument("jobs must be >= 1, got " + std::to_string(options.jobs));
  const int threads_per_run = options.threads_per_run > 0 ? options.threads_per_run : (options.jobs > 1 ? 1 : 0);
  const RunSource source = make_run_source(scene, threads_per_run);  // refuses unavailable sources before any write
  SweepWriter writer(scene, options);
  const std::vector<SweepJob>& pending = writer.pending();
  // One DEM thread per run: its CPU time is the worker thread's; runs one at a time: the process's.
  const bool one_at_a_time = options.jobs == 1 || pending.size() <= 1;
  const CpuClock cpu_clock = threads_per_run == 1 ? CpuClock::kThread : one_at_a_time ? CpuClock::kProcess : CpuClock::kNone;

  if (one_at_a_time) {
    for (const SweepJob& job : pending) {
      writer.started(job);
      const RunTimer timer(cpu_clock);
      std::vector<tables::Run> run;
      try {
        run = source(*job.material, job.rpm);
      } catch (const std::exception& e) {
        writer.failed(job, e.what());
        writer.finish();
        throw;
      }
      writer.finished(job, run, timer.stop());
    }
    return writer.finish();
  }

  // Threads compute, this thread writes (SQLite has one writer): finished runs are handed over in a
  // queue and written in the order they finish. A failed run stops new runs from starting; the ones
  // already finished are still written.
  struct Done {
    const SweepJob* job;
    std::vector<tables::Run> run;
    RunCost cost;
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
        const RunTimer timer(cpu_clock);
        try {
          std::vector<tables::Run> run = source(*pending[i].material, pending[i].rpm);
          const RunCost cost = timer.stop();
          std::lock_guard lock(mutex);
          queue.push_back({&pending[i], std::move(run), cost});
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
      writer.finished(*done.job, done.run, done.cost);
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
