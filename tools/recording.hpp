// SPDX-License-Identifier: MIT
// The recording format lives in the library (elan/recording.hpp, read and written by the program
// recorder too); the command line tools name it in their own namespace.
#pragma once

#include "elan/recording.hpp"

namespace elan::cli {

using elan::check_recording_build;
using elan::check_recording_magic;
using elan::decode_recording;
using elan::encode_recording;
using elan::Keyframe;
using elan::keyframe_at_or_before;
using elan::kRecordingMagicBytes;
using elan::Recording;
using elan::RecordingError;

}  // namespace elan::cli
