// spectrace batch: the jobs of a job file, rendered on one device by a
// Session; a bad job is reported and the others go on. The job file is
// read and counted first (JobReader), then each job is built as it runs.
#include <cstdio>
#include <fmt/format.h>
#include <functional>
#include <future>
#include <optional>
#include <string>
#include <unistd.h>
#include <vector>

#include "cli/commands.h"
#include "cli/progress_line.h"
#include "session/job_file.h"
#include "session/session.h"

namespace spectrace::cli {
namespace {

struct Row {
  std::string job, output, beams, seconds, rate, status;
};

void printTable(const std::vector<Row>& rows) {
  Row head{"job", "output", "beams", "seconds", "Mbeam/s", "status"};
  size_t w[6] = {};
  auto widen = [&](const Row& r) {
    const std::string* cells[6] = {&r.job, &r.output, &r.beams, &r.seconds, &r.rate, &r.status};
    for (int i = 0; i < 6; ++i) w[i] = std::max(w[i], cells[i]->size());
  };
  widen(head);
  for (const auto& r : rows) widen(r);
  auto print = [&](const Row& r) {
    std::printf("%s\n", fmt::format("{:<{}}  {:<{}}  {:>{}}  {:>{}}  {:>{}}  {}", r.job, w[0], r.output, w[1], r.beams,
                                    w[2], r.seconds, w[3], r.rate, w[4], r.status)
                            .c_str());
  };
  print(head);
  for (const auto& r : rows) print(r);
}

// One batch run: jobs rendered one after another on one session, a table
// row each. A job is written while the next one traces.
class BatchRun {
 public:
  BatchRun(const BatchCommand& command, const std::atomic<bool>& cancel, uint64_t total)
      : command_(command), cancel_(cancel), total_(total), progress_(ProgressLine::forStderr()),
        session_(parseDeviceChoice(command.device), logger(), command.pipelineCache) {}

  // Whether no further job may start (interrupted, or --fail-fast after a failure).
  bool stopped() const { return cancel_.load() || (failed_ && command_.failFast); }
  void run(JobEntry& entry);
  // After the last job started: its writing, a row for the `notRun` jobs
  // left, the table. The exit code.
  int finish(uint64_t notRun);

 private:
  // The job being written while the next one traces (Session::renderOverlapped):
  // its row is finished, and its errors reported against it, once its writing ends.
  struct Written {
    size_t row;
    std::shared_future<RenderResult> result;
    uint64_t beams;
  };

  std::function<void(const std::string&)> logger() {
    if (command_.quiet) return {};
    return [this](const std::string& line) { progress_.notice(line); };
  }
  void fail(Row& row, const std::string& message) {
    progress_.notice("error: " + message);
    row.status = "FAILED";
    ++failed_;
  }
  void collect();
  std::string render(JobEntry& entry, size_t row);

  const BatchCommand& command_;
  const std::atomic<bool>& cancel_;
  const uint64_t total_;
  ProgressLine progress_;  // before session_, whose log writes through it
  const Session session_;
  std::vector<Row> rows_;
  size_t failed_ = 0, rendered_ = 0, skipped_ = 0;
  std::optional<Written> writing_;
};

void BatchRun::collect() {
  if (!writing_) return;
  const size_t i = writing_->row;
  Row& row = rows_[i];
  try {
    const RenderResult& result = writing_->result.get();
    row.seconds = fmt::format("{:.2f}", result.wallSeconds);
    row.rate = fmt::format("{:.1f}", double(result.beamsTraced) / result.wallSeconds * 1e-6);
    if (result.beamsTraced < writing_->beams) {
      row.status = "interrupted";
      ++failed_;
    } else {
      row.status = "ok";
      ++rendered_;
    }
    if (!command_.quiet)
      progress_.notice(fmt::format("[{}/{}] {} -> {}: {} beams in {} s ({} Mbeam/s) on {}", i + 1, total_, row.job,
                                   row.output, result.beamsTraced, row.seconds, row.rate, result.deviceName));
  } catch (const OutputError& e) {
    fail(row, fmt::format("{}: /output: {}", row.job, e.what()));
  } catch (const std::exception& e) {
    fail(row, fmt::format("{}: {}", row.job, e.what()));
  }
  writing_.reset();
}

// Starts the job's render (its writing goes on while the next job traces);
// the error that kept it from starting, if any.
std::string BatchRun::render(JobEntry& entry, size_t i) {
  RenderJob& job = *entry.job;
  job.png = command_.png;
  job.loop.cancel = &cancel_;
  job.outputs.downloadFilm = false;  // Session downloads it when the state or the spectral block needs it
  if (!command_.quiet) {
    // Per job, only what is out of the ordinary: notes and warnings, named
    // by the job (the device and estimator would repeat on every job).
    job.loop.log = [this, where = entry.where](const std::string& line) {
      if (line.starts_with("note:") || line.starts_with("warning:")) progress_.notice(where + ": " + line);
    };
    job.loop.onStart = [this, i, where = entry.where](uint64_t done, uint64_t all) {
      progress_.start(all, done, fmt::format("[{}/{}] {}: ", i + 1, total_, where));
    };
    job.loop.onProgress = [this](uint64_t done, uint64_t) { progress_.update(done); };
  }
  try {
    checkOutputPath(job, {command_.jobs});  // the job file is an input too
    auto result = session_.renderOverlapped(job);
    collect();  // the previous job: written by now
    writing_ = Written{i, std::move(result), job.beamCount()};
    // --fail-fast must know this job's outcome before the next one starts.
    if (command_.failFast) collect();
  } catch (const OutputPathError& e) {
    return fmt::format("{}: {}: {}", entry.where, e.role == job.stateRole ? "/state" : "/output", e.what());
  } catch (const OutputError& e) {
    return fmt::format("{}: /output: {}", entry.where, e.what());
  } catch (const std::exception& e) {
    return fmt::format("{}: {}", entry.where, e.what());
  }
  return {};
}

void BatchRun::run(JobEntry& entry) {
  const size_t i = rows_.size();
  rows_.push_back(Row{entry.where, entry.output.string(), entry.beams ? std::to_string(*entry.beams) : "-", "-", "-", ""});
  std::string error;
  if (!entry.job) {
    error = entry.error;
  } else if (command_.skipExisting && outputIsComplete(entry.job->output, entry.job->beamCount())) {
    rows_[i].status = "skipped (complete)";
    ++skipped_;
    if (!command_.quiet)
      progress_.notice(fmt::format("[{}/{}] {}: skipped, {} is complete", i + 1, total_, entry.where, rows_[i].output));
  } else {
    error = render(entry, i);
  }
  if (!error.empty()) {
    collect();  // the previous job's report comes first
    fail(rows_[i], error);
  }
}

int BatchRun::finish(uint64_t notRun) {
  collect();
  progress_.finish();
  if (notRun)  // one row for them all: a job is built only when it is about to run
    rows_.push_back(Row{fmt::format("the other {} job{}", notRun, notRun == 1 ? "" : "s"), "-", "-", "-", "-",
                        cancel_.load() ? "cancelled" : "not run (--fail-fast)"});
  if (!command_.quiet) {
    printTable(rows_);
    std::printf("%s\n", fmt::format("{} jobs: {} rendered, {} skipped, {} failed", total_, rendered_, skipped_,
                                    failed_).c_str());
  }
  if (cancel_.load()) return 130;
  return failed_ ? 2 : 0;
}

}  // namespace

int runBatch(const BatchCommand& command, const std::atomic<bool>& cancel) {
  std::optional<JobReader> reader;
  try {
    reader.emplace(command.jobs, JobReaderOptions{command.outDir, kMaxJobsPerFile, &cancel});
  } catch (const JobFileError& e) {
    std::fprintf(stderr, "spectrace: error: %s\n", e.what());
    return 2;
  } catch (const JobFileCancelled& e) {
    if (!command.quiet) std::fprintf(stderr, "spectrace: %s; nothing was rendered\n", e.what());
    return 130;
  }
  BatchRun batch(command, cancel, reader->total());
  uint64_t started = 0;
  // Jobs are built one at a time, as they come to run.
  while (!batch.stopped()) {
    std::optional<JobEntry> entry = reader->next();
    if (!entry) break;
    batch.run(*entry);
    ++started;
  }
  return batch.finish(reader->total() - started);
}

}  // namespace spectrace::cli
