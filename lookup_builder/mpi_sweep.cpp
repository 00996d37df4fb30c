#include "lookup_builder/mpi_sweep.hpp"

#include <mpi.h>

#include <atomic>
#include <chrono>
#include <cstdint>
#include <cstring>
#include <span>
#include <deque>
#include <exception>
#include <mutex>
#include <optional>
#include <stdexcept>
#include <thread>

#include "lookup_builder/run_message.hpp"
#include "lookup_builder/run_source.hpp"

namespace spread::lookup {
namespace {

// Message tags. A worker sends kRequest once, then kResult or kError per job; rank 0 answers every
// one of them with kJob carrying the next job index (int64) or −1 = no more work.
constexpr int kRequest = 1;
constexpr int kJob = 2;
constexpr int kResult = 3;
constexpr int kError = 4;

using Clock = std::chrono::steady_clock;

void send_job(int worker, std::int64_t index) {
  MPI_Send(&index, 1, MPI_INT64_T, worker, kJob, MPI_COMM_WORLD);
}

std::vector<std::uint8_t> receive_bytes(const MPI_Status& probe) {
  int count = 0;
  MPI_Get_count(&probe, MPI_BYTE, &count);
  std::vector<std::uint8_t> bytes(static_cast<std::size_t>(count));
  MPI_Recv(bytes.data(), count, MPI_BYTE, probe.MPI_SOURCE, probe.MPI_TAG, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
  return bytes;
}

void run_worker(const scene::Scene& scene, const RunSource& source) {
  const std::vector<SweepJob> jobs = sweep_jobs(scene);
  MPI_Send(nullptr, 0, MPI_BYTE, 0, kRequest, MPI_COMM_WORLD);
  for (;;) {
    std::int64_t index = -1;
    MPI_Recv(&index, 1, MPI_INT64_T, 0, kJob, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
    if (index < 0 || index >= static_cast<std::int64_t>(jobs.size())) return;
    const SweepJob& job = jobs[static_cast<std::size_t>(index)];
    std::vector<std::uint8_t> message;
    int tag = kResult;
    const auto start = Clock::now();
    try {
      message = serialise_runs(source(*job.material, job.rpm));
    } catch (const std::exception& e) {
      const std::string what = e.what();
      message.assign(what.begin(), what.end());
      tag = kError;
    }
    // The compute time travels in front of the run so rank 0's log shows it.
    const double seconds = std::chrono::duration<double>(Clock::now() - start).count();
    std::vector<std::uint8_t> framed(sizeof seconds);
    std::memcpy(framed.data(), &seconds, sizeof seconds);
    framed.insert(framed.end(), message.begin(), message.end());
    MPI_Send(framed.data(), static_cast<int>(framed.size()), MPI_BYTE, 0, tag, MPI_COMM_WORLD);
  }
}

}  // namespace

BuildSummary build_tables_mpi(const scene::Scene& scene, const BuildOptions& options) {
  int rank = 0, size = 1;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  // One run per rank at a time; each run uses one thread unless told otherwise (ranks share the cores).
  const RunSource source = make_run_source(scene, options.threads_per_run > 0 ? options.threads_per_run : 1);
  if (rank != 0) {
    run_worker(scene, source);
    return {};
  }

  // Rank 0. A file that is not ours is refused before any work; the workers are then told to stop.
  std::optional<SweepWriter> writer;
  std::exception_ptr open_error;
  try {
    writer.emplace(scene, options);
  } catch (...) {
    open_error = std::current_exception();
  }
  const std::vector<SweepJob> all = sweep_jobs(scene);
  const std::vector<SweepJob> pending = writer ? writer->pending() : std::vector<SweepJob>{};
  std::atomic<std::size_t> next{0};
  std::atomic<bool> stop{false};
  std::string failure;

  // Rank 0's own share, on a thread that never calls MPI (MPI_THREAD_FUNNELED is enough).
  struct Done {
    const SweepJob* job;
    std::optional<std::vector<tables::Run>> run;
    std::string error;
    double seconds;
  };
  std::mutex mutex;
  std::deque<Done> local_done;
  std::atomic<bool> local_finished{false};
  std::thread local([&] {
    for (std::size_t i; !stop && (i = next++) < pending.size();) {
      {
        std::lock_guard lock(mutex);
        writer->started(pending[i]);
      }
      const auto start = Clock::now();
      Done done{&pending[i], std::nullopt, {}, 0.0};
      try {
        done.run = source(*pending[i].material, pending[i].rpm);
      } catch (const std::exception& e) {
        done.error = e.what();
        stop = true;
      }
      done.seconds = std::chrono::duration<double>(Clock::now() - start).count();
      std::lock_guard lock(mutex);
      local_done.push_back(std::move(done));
    }
    local_finished = true;
  });

  std::vector<const SweepJob*> assigned(static_cast<std::size_t>(size), nullptr);
  auto hand_out = [&](int worker) {
    const std::size_t i = stop ? pending.size() : next++;
    if (i < pending.size()) {
      assigned[static_cast<std::size_t>(worker)] = &pending[i];
      {
        std::lock_guard lock(mutex);
        writer->started(pending[i]);
      }
      send_job(worker, pending[i].index);
      return true;
    }
    send_job(worker, -1);
    return false;
  };
  auto record = [&](const SweepJob& job, const std::optional<std::vector<tables::Run>>& run, const std::string& error,
                    double seconds) {
    if (!run) {
      if (failure.empty()) failure = job.label() + ": " + error;
      writer->failed(job, error);
      stop = true;
      return;
    }
    if (!failure.empty()) return;
    try {
      writer->finished(job, *run, RunCost{seconds, -1.0});
    } catch (const std::exception& e) {
      failure = job.label() + ": writing: " + e.what();
      stop = true;
    }
  };

  int workers_active = size - 1;
  for (;;) {
    std::deque<Done> ready;
    {
      std::lock_guard lock(mutex);
      ready.swap(local_done);
    }
    for (const Done& d : ready) record(*d.job, d.run, d.error, d.seconds);
    if (workers_active == 0 && local_finished) {
      std::lock_guard lock(mutex);
      if (local_done.empty()) break;
      continue;
    }
    int flag = 0;
    MPI_Status status;
    MPI_Iprobe(MPI_ANY_SOURCE, MPI_ANY_TAG, MPI_COMM_WORLD, &flag, &status);
    if (!flag) {
      std::this_thread::sleep_for(std::chrono::milliseconds(2));
      continue;
    }
    const int worker = status.MPI_SOURCE;
    std::vector<std::uint8_t> bytes = receive_bytes(status);
    if (status.MPI_TAG == kResult || status.MPI_TAG == kError) {
      const SweepJob* job = assigned[static_cast<std::size_t>(worker)];
      double seconds = 0.0;
      if (bytes.size() >= sizeof seconds) std::memcpy(&seconds, bytes.data(), sizeof seconds);
      const std::span<const std::uint8_t> body =
          std::span<const std::uint8_t>(bytes).subspan(std::min(bytes.size(), sizeof seconds));
      std::optional<std::vector<tables::Run>> run;
      std::string error;
      if (status.MPI_TAG == kResult) {
        try {
          run = deserialise_runs(body);
        } catch (const std::exception& e) {
          error = std::string("from rank ") + std::to_string(worker) + ": " + e.what();
        }
      } else {
        error = "on rank " + std::to_string(worker) + ": " + std::string(body.begin(), body.end());
      }
      if (job != nullptr) record(*job, run, error, seconds);
    }
    if (!hand_out(worker)) --workers_active;
  }
  local.join();
  if (open_error) std::rethrow_exception(open_error);
  const BuildSummary summary = writer->finish();
  if (!failure.empty()) throw std::runtime_error(failure);
  return summary;
}

}  // namespace spread::lookup
