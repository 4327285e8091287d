#include "sfm_app/run_junction_sfm.h"

#include <gflags/gflags.h>
#include <glog/logging.h>
#include <unistd.h>

#include <cctype>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <memory>
#include <mutex>
#include <new>
#include <opencv2/core.hpp>

#include "util/output_directory.h"
#include "util/status.h"
#include "pipeline/pipeline_outputs.h"

namespace sfm {
namespace {

std::string OneLine(std::string text) {
  for (char& c : text) {
    if (c == '\n' || c == '\r') c = ' ';
  }
  while (!text.empty() && text.back() == ' ') text.pop_back();
  return text;
}

bool FlagIsDefault(const char* name) {
  gflags::CommandLineFlagInfo info;
  return !gflags::GetCommandLineFlagInfo(name, &info) || info.is_default;
}

// glog's INFO and WARNING lines of the run, written to junction_sfm.log in the output directory.
class LogFileSink : public google::LogSink {
 public:
  explicit LogFileSink(const std::string& path) : file_(std::fopen(path.c_str(), "w")) {}
  ~LogFileSink() override { Close(); }
  bool ok() const { return file_ != nullptr; }

  void send(google::LogSeverity severity, const char* /*full_filename*/, const char* base_filename, int line,
            const google::LogMessageTime& time, const char* message, size_t message_len) override {
    std::lock_guard<std::mutex> lock(mutex_);
    if (!file_) return;
    const std::string text = ToString(severity, base_filename, line, time, message, message_len);
    std::fprintf(file_, "%s\n", text.c_str());
    std::fflush(file_);
  }

  void Close() {
    std::lock_guard<std::mutex> lock(mutex_);
    if (file_) std::fclose(file_);
    file_ = nullptr;
  }

 private:
  std::mutex mutex_;
  std::FILE* file_;
};

// An exception that escapes a worker thread (std::bad_alloc in a Ceres or OpenCV thread) ends the
// process through std::terminate: still one line, and no staging directory left behind.
[[noreturn]] void OnTerminate() {
  OutputDirectory::EmergencyCleanup();
  std::string what = "terminated by an unhandled exception";
  if (const std::exception_ptr exception = std::current_exception()) {
    try {
      std::rethrow_exception(exception);
    } catch (const std::bad_alloc&) {
      what = "out of memory (std::bad_alloc)";
    } catch (const cv::Exception& e) {
      what =
          std::string(e.code == cv::Error::StsNoMem ? "out of memory" : "OpenCV error") + " (" + e.err + ")";
    } catch (const std::exception& e) {
      what = e.what();
    } catch (...) {
    }
  }
  std::fprintf(stderr, "junction_sfm: %s\n", OneLine(what).c_str());
  std::_Exit(1);
}

// A failed CHECK is a bug: glog has printed it; the staging directory is removed before the abort.
void OnFatal() {
  OutputDirectory::EmergencyCleanup();
  std::abort();
}

}  // namespace

void ConfigureLogging() {
  if (FlagIsDefault("logtostderr")) FLAGS_logtostderr = false;
  if (FlagIsDefault("stderrthreshold")) FLAGS_stderrthreshold = google::GLOG_WARNING;
  if (FlagIsDefault("alsologtostderr") && FLAGS_v > 0) FLAGS_alsologtostderr = true;
  // No glog files in /tmp: the run's log is junction_sfm.log in its output directory.
  if (FlagIsDefault("log_dir")) {
    for (const google::LogSeverity severity :
         {google::GLOG_INFO, google::GLOG_WARNING, google::GLOG_ERROR, google::GLOG_FATAL}) {
      google::SetLogDestination(severity, "");
    }
  }
}

std::string FlagMessage(const std::string& message,
                        const std::vector<std::pair<std::string, std::string>>& field_flags) {
  auto is_name_char = [](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; };
  for (const auto& [field, flag] : field_flags) {
    for (size_t at = message.find(field); at != std::string::npos; at = message.find(field, at + 1)) {
      const size_t end = at + field.size();
      if ((at > 0 && is_name_char(message[at - 1])) || (end < message.size() && is_name_char(message[end]))) {
        continue;
      }
      std::string value;
      gflags::GetCommandLineOption(flag.c_str(), &value);
      std::string rule = message.substr(end);
      const size_t must = rule.find("must");
      if (must != std::string::npos) rule = rule.substr(must);
      while (!rule.empty() && (rule[0] == ' ' || rule[0] == ':')) rule.erase(0, 1);
      return "--" + flag + "=" + value + ": " + rule;
    }
  }
  return message;
}

int RunIntoOutputDirectory(PipelineOptions options) {
  std::unique_ptr<OutputDirectory> directory;
  if (const Status open = OutputDirectory::Open(options.output_dir, OutputEntryNames(), &directory);
      !open.ok()) {
    std::fprintf(stderr, "junction_sfm: %s\n", open.message().c_str());
    return 1;
  }
  directory->RemoveOnSignals();
  std::set_terminate(OnTerminate);
  google::InstallFailureFunction(&OnFatal);
  const std::string log_path = (std::filesystem::path(directory->staging()) / kLogFileName).string();
  LogFileSink sink(log_path);
  if (!sink.ok()) {
    std::fprintf(stderr, "junction_sfm: %s: cannot be written\n", directory->UserPath(log_path).c_str());
    return 1;
  }
  google::AddLogSink(&sink);
  LOG(INFO) << "output directory " << directory->target() << " (written in " << directory->staging()
            << " and moved into place at the end)";

  options.output_dir = directory->staging();
  PipelineResult result;
  Status status;
  try {
    status = RunPipeline(options, &result);
  } catch (const std::bad_alloc&) {
    status = Status::Error("out of memory (std::bad_alloc); the images may be too large for this machine");
  } catch (const cv::Exception& e) {
    status = Status::Error(e.code == cv::Error::StsNoMem
                               ? "out of memory (OpenCV: " + OneLine(e.err) + "); the images may be too large"
                               : "OpenCV error in " + e.func + ": " + OneLine(e.err));
  } catch (const std::exception& e) {
    status = Status::Error(std::string("unexpected error: ") + OneLine(e.what()));
  }
  google::RemoveLogSink(&sink);
  sink.Close();
  if (status.ok()) status = directory->Commit();
  if (!status.ok()) {
    const std::string message = directory->UserPath(status.message());
    directory.reset();  // the staging directory removed before the message
    std::fprintf(stderr, "junction_sfm: %s\n", OneLine(message).c_str());
    return 1;
  }
  std::fprintf(stderr,
               "junction_sfm: %zu frames, %zu tracks, %zu points, %zu lines in %.1f s; outputs in %s\n",
               result.junctions.size(), result.tracks.size(), result.landmarks.points.size(),
               result.landmarks.lines.size(), result.times.total, directory->target().c_str());
  return 0;
}

}  // namespace sfm
