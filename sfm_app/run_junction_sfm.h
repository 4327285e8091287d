// What junction_sfm's main does around RunPipeline, so that every failure is one line on stderr
// and the output directory is one unit (SPEC section 2; docs/user_guide.md, "Errors and the output
// directory").
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "pipeline/pipeline.h"

namespace sfm {

// stderr is for the user: glog's INFO lines go to junction_sfm.log in the output directory, only
// warnings and errors to stderr. A user's own --logtostderr, --alsologtostderr or
// --stderrthreshold is kept; --v=1 or more also shows INFO on stderr. Call after parsing the
// flags and InitGoogleLogging.
void ConfigureLogging();

// An option struct's Check() message rewritten to name the flag a user typed: for each pair
// (option field, flag) whose field the message names, "--<flag>=<value>: must be ...". Messages
// that name no listed field are returned as they are.
std::string FlagMessage(const std::string& message,
                        const std::vector<std::pair<std::string, std::string>>& field_flags);

// Runs the pipeline into a staging directory beside options.output_dir and swaps it into place
// when the run succeeds (OutputDirectory). Catches std::bad_alloc, cv::Exception and every other
// std::exception: one line on stderr, the staging directory removed. Ends with one summary line
// naming the output directory. Returns the process exit status: 0, or 1 after a one-line error.
int RunIntoOutputDirectory(PipelineOptions options);

}  // namespace sfm
