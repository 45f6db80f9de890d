// spectrace batch: the jobs of a job file, rendered on one device by a
// Session; a bad job is reported and the others go on.
#include <chrono>
#include <cstdio>
#include <fmt/format.h>
#include <future>
#include <optional>
#include <unistd.h>
#include <vector>

#include "cli/commands.h"
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

}  // namespace

int runBatch(const BatchCommand& command, const std::atomic<bool>& cancel) {
  std::vector<JobEntry> entries;
  try {
    entries = readJobFile(command.jobs, command.outDir);
  } catch (const JobFileError& e) {
    std::fprintf(stderr, "spectrace: error: %s\n", e.what());
    return 2;
  }
  const bool live = !command.quiet && isatty(STDERR_FILENO);
  std::function<void(const std::string&)> log;
  if (!command.quiet) log = [](const std::string& line) { std::fprintf(stderr, "spectrace: %s\n", line.c_str()); };
  const Session session(parseDeviceChoice(command.device), log, command.pipelineCache);

  std::vector<Row> rows;
  size_t failed = 0, rendered = 0, skipped = 0;
  const size_t total = entries.size();
  auto fail = [&](Row& row, const std::string& message) {
    std::fprintf(stderr, "%sspectrace: error: %s\n", live ? "\r\033[K" : "", message.c_str());
    row.status = "FAILED";
    ++failed;
  };
  // The job being written while the next one traces (Session::renderOverlapped):
  // its row is finished, and its errors reported against it, once its writing ends.
  struct Written {
    size_t index;
    std::shared_future<RenderResult> result;
    uint64_t beams;
  };
  std::optional<Written> writing;
  auto collect = [&]() {
    if (!writing) return;
    const size_t i = writing->index;
    Row& row = rows[i];
    const JobEntry& entry = entries[i];
    try {
      const RenderResult& result = writing->result.get();
      row.seconds = fmt::format("{:.2f}", result.wallSeconds);
      row.rate = fmt::format("{:.1f}", double(result.beamsTraced) / result.wallSeconds * 1e-6);
      if (result.beamsTraced < writing->beams) {
        row.status = "interrupted";
        ++failed;
      } else {
        row.status = "ok";
        ++rendered;
      }
      if (!command.quiet)
        std::fprintf(stderr, "%sspectrace: [%zu/%zu] %s -> %s: %llu beams in %s s (%s Mbeam/s) on %s\n",
                     live ? "\r\033[K" : "", i + 1, total, entry.where.c_str(), row.output.c_str(),
                     (unsigned long long)result.beamsTraced, row.seconds.c_str(), row.rate.c_str(),
                     result.deviceName.c_str());
    } catch (const OutputError& e) {
      fail(row, fmt::format("{}: /output: {}", entry.where, e.what()));
    } catch (const std::exception& e) {
      fail(row, fmt::format("{}: {}", entry.where, e.what()));
    }
    writing.reset();
  };
  for (size_t i = 0; i < total; ++i) {
    JobEntry& entry = entries[i];
    rows.push_back(Row{entry.where, entry.output.string(), entry.beams ? std::to_string(*entry.beams) : "-", "-", "-", ""});
    std::string error;
    if (cancel.load()) {
      rows[i].status = "cancelled";
    } else if (!entry.job) {
      error = entry.error;
    } else if (command.skipExisting && outputIsComplete(entry.job->output, entry.job->beamCount())) {
      rows[i].status = "skipped (complete)";
      ++skipped;
      if (!command.quiet) std::fprintf(stderr, "spectrace: [%zu/%zu] %s: skipped, %s is complete\n", i + 1, total,
                                       entry.where.c_str(), rows[i].output.c_str());
    } else {
      RenderJob& job = *entry.job;
      job.png = command.png;
      job.loop.cancel = &cancel;
      job.outputs.downloadFilm = false;  // Session downloads it when the state or the spectral block needs it
      if (live)
        job.loop.onProgress = [&, i](uint64_t done, uint64_t all) {
          std::fprintf(stderr, "\r\033[Kspectrace: [%zu/%zu] %s: %5.1f%%", i + 1, total, entries[i].where.c_str(),
                       100.0 * double(done) / double(all));
        };
      try {
        checkOutputPath(job, {command.jobs});  // the job file is an input too
        auto result = session.renderOverlapped(job);
        collect();  // the previous job: written by now
        writing = Written{i, std::move(result), job.beamCount()};
        // --fail-fast must know this job's outcome before the next one starts.
        if (command.failFast) collect();
      } catch (const OutputError& e) {
        error = fmt::format("{}: /output: {}", entry.where, e.what());
      } catch (const std::exception& e) {
        error = fmt::format("{}: {}", entry.where, e.what());
      }
    }
    if (!error.empty()) {
      collect();  // the previous job's report comes first
      fail(rows[i], error);
    }
    if (failed && command.failFast) {
      for (size_t j = i + 1; j < total; ++j)
        rows.push_back(Row{entries[j].where, entries[j].output.string(), "-", "-", "-", "not run (--fail-fast)"});
      break;
    }
  }
  collect();
  if (!command.quiet) {
    printTable(rows);
    std::printf("%zu jobs: %zu rendered, %zu skipped, %zu failed\n", total, rendered, skipped, failed);
  }
  if (cancel.load()) return 130;
  return failed ? 2 : 0;
}

}  // namespace spectrace::cli
