// --trace-pixel X Y and --trace-json FILE: the checks made before rendering, and the report of the
// recorded camera samples (render/path_recorder.h) as text on stdout and as JSON.
#pragma once

#include <string>

#include "core/vec.h"
#include "render/path_recorder.h"

namespace phos::app {

struct RunOptions;

// Throws InputError (exit 2) before any work when the pixel lies outside a width x height image,
// when --trace-json comes without --trace-pixel, or when its file cannot be written.
void check_trace_options(const RunOptions& run, int width, int height);

// What the report says besides the paths.
struct TraceHeader {
    std::string integrator;
    Rgb value;  // the pixel's value in the image
};

// One block per camera sample (PPM / SPPM: per eye path, with its visible point, photon passes and
// statistics), then the pixel's value.
std::string trace_text(const render::PathRecorder& trace, const TraceHeader& header);
// {"pixel": [x, y], "integrator": ..., "value": [r, g, b], "paths": [{"sample": s, "vertices": [...],
// "contribution": [r, g, b]}, ...]} (docs/usage.md lists every field).
std::string trace_json(const render::PathRecorder& trace, const TraceHeader& header);

// Prints trace_text to stdout and writes trace_json to `json_path` (if not empty) atomically.
void report_trace(const render::PathRecorder& trace, const TraceHeader& header, const std::string& json_path);

}  // namespace phos::app
