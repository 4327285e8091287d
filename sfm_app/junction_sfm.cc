// junction_sfm: junction-based structure from motion on a sequence (SPEC section 2).
//
//   build/bin/junction_sfm --sequence <sequence dir> --output <output dir>
//
// Without --sequence it runs the default sequence shipped under sequences/default.
#include <cstdio>
#include <string>

#include <gflags/gflags.h>
#include <glog/logging.h>

#include "sfm_app/pipeline.h"

DEFINE_string(sequence, SFM_DEFAULT_SEQUENCE,
              "Sequence directory (SPEC section 1: sequence.yaml, images.txt, odometry.txt, "
              "optional groundtruth.txt). Default: the sequence shipped in sequences/default.");
DEFINE_string(output, "output", "Output directory; created if missing, files of the same names replaced.");
DEFINE_bool(progress, true, "Show a progress line on stderr (only when stderr is a terminal).");

int main(int argc, char** argv) {
  gflags::SetUsageMessage(
      "junction-based structure from motion.\n"
      "  junction_sfm --sequence <sequence dir> --output <output dir> [flags]");
  gflags::SetVersionString("0.1.0");
  gflags::ParseCommandLineFlags(&argc, &argv, true);
  FLAGS_logtostderr = true;
  google::InitGoogleLogging(argv[0]);

  if (argc > 1) {
    std::fprintf(stderr, "junction_sfm: unexpected argument '%s' (flags are --name=value; see --help)\n", argv[1]);
    return 2;
  }
  if (FLAGS_output.empty()) {
    std::fprintf(stderr, "junction_sfm: --output must name a directory\n");
    return 2;
  }

  sfm::PipelineOptions options;
  options.sequence_dir = FLAGS_sequence;
  options.output_dir = FLAGS_output;
  options.show_progress = FLAGS_progress;
  const sfm::Status status = sfm::RunPipeline(options);
  if (!status.ok()) {
    std::fprintf(stderr, "junction_sfm: %s\n", status.message().c_str());
    return 1;
  }
  return 0;
}
