// Reading a data set's files with one-line messages that name the file (and line): the small
// ASCII files (matrices, point lists, camera files) and the images.
#pragma once

#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "util/status.h"

namespace sfm {

// Every whitespace-separated token of the file as a number, in file order. Fails, naming the file
// (and line), when it cannot be opened or a token is not a finite number.
Status ReadNumbers(const std::string& path, std::vector<double>* numbers);

// Decodes an image with cv::imread(path, flags). OpenCV and its codec libraries print their
// diagnostics to stderr, which would break the programs' one-line errors, so they are caught and
// put in the message instead. Fails when nothing decodes, and when libjpeg reports a truncated
// file (it then still returns an image, grey below the cut); other codec warnings are logged.
Status DecodeImage(const std::string& path, int flags, cv::Mat* image);

// The same for an encoded image held in memory (cv::imdecode), e.g. a ROS CompressedImage
// message; `where` names it in the messages.
Status DecodeImageBytes(const std::string& where, const std::vector<unsigned char>& bytes, int flags,
                        cv::Mat* image);

}  // namespace sfm
