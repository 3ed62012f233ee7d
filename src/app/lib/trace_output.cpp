// The report of --trace-pixel (see trace_output.h): text for people, JSON for tools.
#include "app/lib/trace_output.h"

#include <cstdio>
#include <filesystem>
#include <fstream>

#include "app/lib/json_writer.h"
#include "app/lib/render_options.h"
#include "core/error.h"
#include "core/format.h"
#include "integrators/registry.h"
#include "io/image/atomic_write.h"

namespace phos::app {
namespace {

using render::kTraceTerms;
using render::TracedLight;
using render::TracedLookup;
using render::TracedPass;
using render::TracedPath;
using render::TracedVertex;
using render::TracedVisiblePoint;
using render::TraceTerm;

// Photons listed per pass in the text (the JSON has them all).
constexpr size_t kTextPhotons = 8;

// ---- text ----

std::string num(double v) { return printf_string("%.4g", v); }
std::string vec(Vec3 v) { return "(" + num(v.x) + ", " + num(v.y) + ", " + num(v.z) + ")"; }
std::string rgb(Rgb c) { return num(c.r) + " " + num(c.g) + " " + num(c.b); }
// A spectrum at the path's wavelengths: its values in brackets.
std::string spec(const Spectrum& s) {
    std::string out = "[";
    for (int i = 0; i < spectrum::kSpectrumSamples; ++i) out += (i ? " " : "") + num(s[i]);
    return out + "]";
}

// The surface or medium a vertex lies in: "shape 4 (scene.scn:12), material 1 "white"".
std::string where(const TracedVertex& v) {
    std::string s;
    if (v.surface) {
        s += ", shape " + std::to_string(v.shape);
        if (v.instance >= 0) s += " of instance " + std::to_string(v.instance);
        if (!v.shape_name.empty()) s += " (" + v.shape_name + ")";
        s += ", material " + std::to_string(v.material);
        if (!v.material_name.empty()) s += " \"" + v.material_name + "\"";
        if (v.area_light >= 0) s += ", area light " + std::to_string(v.area_light);
    }
    if (v.medium >= 0) s += (v.surface ? ", arriving in medium " : ", medium ") + std::to_string(v.medium);
    return s;
}

void text_light(std::string& out, const TracedLight& l) {
    out += "      light " + std::to_string(l.light) + " from " + vec(l.from) + " towards " + vec(l.direction);
    if (l.distance < kInf) out += " at " + num(l.distance);
    if (l.visible < 0) {
        out += ": no shadow ray (no light that way, or the surface reflects none of it)\n";
        return;
    }
    out += ", pdf " + num(l.pdf);
    if (l.mis_weight != 1) out += ", MIS weight " + num(l.mis_weight);
    out += l.visible ? ", visible" : ", blocked";
    if (l.visible && !(l.transmittance == Spectrum(1.0f)))
        out += " (transmittance " + spec(l.transmittance) + ")";
    out += ", contribution " + spec(l.contribution) + "\n";
}

void text_lookup(std::string& out, const TracedLookup& l) {
    out += "      lookup " + l.map + " at " + vec(l.position);
    if (l.radius > 0) out += ": " + std::to_string(l.found) + " photons within " + num(l.radius);
    out += ", estimate " + rgb(l.estimate) + "\n";
}

// What a vertex (or the camera ray) added, its light samples and lookups.
void text_details(std::string& out, const TracedVertex& v) {
    for (const TracedLight& l : v.lights) text_light(out, l);
    for (const TracedLookup& l : v.lookups) text_lookup(out, l);
    std::string adds;
    for (int t = 0; t < kTraceTerms; ++t)
        if (!v.terms[t].is_black())
            adds += (adds.empty() ? "" : ", ") + std::string(render::trace_term_name(TraceTerm(t))) + " " +
                    rgb(v.terms[t]);
    if (!adds.empty()) out += "      adds " + adds + "\n";
}

void text_vertex(std::string& out, size_t index, const TracedVertex& v) {
    out += "  " + std::to_string(index) + " " + render::trace_event_name(v.event);
    if (v.placed) out += " at " + vec(v.position);
    if (v.event == render::TraceEvent::Escaped) out += " along " + vec(v.direction);
    out += where(v) + ", throughput " + spec(v.throughput) + "\n";
    text_details(out, v);
    if (v.sampled)
        out += "      goes on along " + vec(v.direction) + ", pdf " + num(v.pdf) + ", weight " +
               spec(v.weight) + (v.dispersed ? " (dispersed: the hero wavelength goes on alone)" : "") + "\n";
}

void text_pass(std::string& out, const TracedPass& p) {
    out += "    photon pass of iteration " + std::to_string(p.iteration) + (p.pilot ? " (pilot)" : "") +
           ": radius " + num(p.radius) + ", " + std::to_string(p.photons.size()) + " photons gathered\n";
    for (size_t i = 0; i < p.photons.size() && i < kTextPhotons; ++i) {
        const auto& ph = p.photons[i];
        out += "      photon " + std::to_string(ph.index) + " at " + vec(ph.position) + " from " +
               vec(ph.wi) + ", power " + rgb(ph.power) + ", f*power " + rgb(ph.contribution) + "\n";
    }
    if (p.photons.size() > kTextPhotons)
        out +=
            "      ... " + std::to_string(p.photons.size() - kTextPhotons) + " more (--trace-json has all)\n";
    out += "      after: N " + num(p.n) + ", R " + num(std::sqrt(p.r2)) + ", tau " + num(p.tau[0]) + " " +
           num(p.tau[1]) + " " + num(p.tau[2]) + ", direct sum " + num(p.direct[0]) + " " + num(p.direct[1]) +
           " " + num(p.direct[2]) + ", photons emitted " + std::to_string(p.photons_emitted) + "\n";
}

void text_visible_point(std::string& out, const TracedVisiblePoint& vp) {
    out += "  visible point (slot " + std::to_string(vp.slot) + ") at " + vec(vp.position);
    if (vp.medium >= 0) out += " in medium " + std::to_string(vp.medium);
    if (vp.material >= 0)
        out += ", material " + std::to_string(vp.material) + " \"" + vp.material_name + "\"";
    out += ", throughput " + spec(vp.throughput) + "\n";
    for (const TracedPass& p : vp.passes) text_pass(out, p);
}

// ---- JSON ----

void json_details(JsonWriter& w, const TracedVertex& v) {
    w.key("radiance").begin_object();
    for (int t = 0; t < kTraceTerms; ++t)
        if (!v.terms[t].is_black()) w.field(render::trace_term_name(TraceTerm(t)), v.terms[t]);
    w.end_object();
    w.key("lights").begin_array();
    for (const TracedLight& l : v.lights) {
        w.begin_object().field("light", l.light).field("from", l.from).field("direction", l.direction);
        w.key("distance");
        if (l.distance < kInf)
            w.value(l.distance);
        else
            w.null();
        w.field("pdf", l.pdf).field("mis_weight", l.mis_weight).key("visible");
        if (l.visible < 0)
            w.null();
        else
            w.value(l.visible == 1);
        w.field("transmittance", l.transmittance).field("contribution", l.contribution).end_object();
    }
    w.end_array();
    w.key("lookups").begin_array();
    for (const TracedLookup& l : v.lookups)
        w.begin_object()
            .field("map", l.map)
            .field("position", l.position)
            .field("found", l.found)
            .field("radius", l.radius)
            .field("estimate", l.estimate)
            .end_object();
    w.end_array();
}

void json_vertex(JsonWriter& w, const TracedVertex& v) {
    w.begin_object(6).field("event", render::trace_event_name(v.event));
    if (v.placed) w.field("position", v.position);
    if (v.surface) {
        w.field("normal", v.normal).field("shape", v.shape);
        if (v.instance >= 0) w.field("instance", v.instance);
        w.field("shape_name", v.shape_name)
            .field("material", v.material)
            .field("material_name", v.material_name);
        if (v.area_light >= 0) w.field("area_light", v.area_light);
    }
    if (v.medium >= 0) w.field("medium", v.medium);
    w.field("throughput", v.throughput);
    if (v.sampled || v.event == render::TraceEvent::Escaped) w.field("direction", v.direction);
    if (v.sampled) w.field("pdf", v.pdf).field("weight", v.weight);
    json_details(w, v);
    w.end_object();
}

void json_visible_point(JsonWriter& w, const TracedVisiblePoint& vp) {
    w.begin_object().field("slot", uint64_t(vp.slot)).field("position", vp.position);
    if (vp.material >= 0) w.field("material", vp.material).field("material_name", vp.material_name);
    if (vp.medium >= 0) w.field("medium", vp.medium);
    w.field("throughput", vp.throughput).key("passes").begin_array();
    for (const TracedPass& p : vp.passes) {
        w.begin_object(6)
            .field("iteration", p.iteration)
            .field("pilot", p.pilot)
            .field("radius", p.radius)
            .field("found", uint64_t(p.photons.size()))
            .key("photons")
            .begin_array();
        for (const auto& ph : p.photons)
            w.begin_object(8)
                .field("index", ph.index)
                .field("position", ph.position)
                .field("power", ph.power)
                .field("wi", ph.wi)
                .field("contribution", ph.contribution)
                .end_object();
        w.end_array().field("n", p.n).field("r2", p.r2);
        w.key("tau").begin_array().value(p.tau[0]).value(p.tau[1]).value(p.tau[2]).end_array();
        w.key("direct_sum")
            .begin_array()
            .value(p.direct[0])
            .value(p.direct[1])
            .value(p.direct[2])
            .end_array();
        w.field("photons_emitted", p.photons_emitted).end_object();
    }
    w.end_array().end_object();
}

// "a, b and c".
std::string listed(const std::vector<std::string>& words) {
    std::string out;
    for (size_t i = 0; i < words.size(); ++i)
        out += (i == 0 ? "" : i + 1 == words.size() ? " and " : ", ") + words[i];
    return out;
}

}  // namespace

void check_trace_options(const RunOptions& run, int width, int height) {
    const bool traced = run.trace_x >= 0 || run.trace_y >= 0;
    if (!traced) {
        if (!run.trace_json.empty()) throw InputError("--trace-json: give the pixel with --trace-pixel X Y");
        return;
    }
    if (!integrators::integrator(run.integrator).traces) {
        std::vector<std::string> tracing;
        for (const integrators::IntegratorInfo& i : integrators::integrators())
            if (i.traces) tracing.push_back(i.name);
        throw InputError("--trace-pixel: the " + integrators::integrator(run.integrator).name +
                         " integrator does not record pixel traces (" + listed(tracing) + " do)");
    }
    if (run.trace_x >= width || run.trace_y >= height)
        throw InputError("--trace-pixel: (" + std::to_string(run.trace_x) + ", " +
                         std::to_string(run.trace_y) + ") is outside the " + std::to_string(width) + "x" +
                         std::to_string(height) + " image");
    if (run.trace_json.empty()) return;
    const std::filesystem::path dir = std::filesystem::absolute(run.trace_json).parent_path();
    if (!std::filesystem::is_directory(dir))
        throw InputError("--trace-json '" + run.trace_json + "': directory '" + dir.string() +
                         "' does not exist");
    if (std::filesystem::is_directory(run.trace_json))
        throw InputError("--trace-json '" + run.trace_json + "' is a directory");
}

std::string trace_text(const render::PathRecorder& trace, const TraceHeader& header) {
    const auto& paths = trace.paths();
    const bool progressive = !paths.empty() && paths.front().visible_point.has_value();
    std::string out = "trace of pixel (" + std::to_string(trace.x()) + ", " + std::to_string(trace.y()) +
                      "), " + header.integrator + ", " + std::to_string(paths.size()) + " camera paths\n";
    for (const TracedPath& p : paths) {
        out += p.iteration >= 0 ? "iteration " + std::to_string(p.iteration)
                                : "sample " + std::to_string(p.sample);
        out += ": contribution " + rgb(p.contribution) +
               (p.visible_point || progressive ? " (emission and direct light)\n" : "\n");
        out += "  wavelengths";
        for (int i = 0; i < spectrum::kSpectrumSamples; ++i)
            out += " " + num(p.lambda[size_t(i)]) + " nm (pdf " + num(p.lambda_pdf[size_t(i)]) + ")";
        out += "\n";
        if (!p.camera.empty()) {
            out += "  camera ray\n";
            text_details(out, p.camera);
        }
        for (size_t i = 0; i < p.vertices.size(); ++i) text_vertex(out, i + 1, p.vertices[i]);
        if (p.visible_point) text_visible_point(out, *p.visible_point);
    }
    out += "pixel value " + rgb(header.value) + "\n";
    return out;
}

std::string trace_json(const render::PathRecorder& trace, const TraceHeader& header) {
    JsonWriter w;
    w.begin_object();
    w.key("pixel").begin_array().value(trace.x()).value(trace.y()).end_array();
    w.field("integrator", header.integrator).field("value", header.value).key("paths").begin_array();
    for (const TracedPath& p : trace.paths()) {
        w.begin_object(2).field("sample", p.sample);
        if (p.iteration >= 0) w.field("iteration", p.iteration);
        if (!p.camera.empty()) {  // what the camera ray added before its first vertex (media)
            w.key("camera").begin_object();
            json_details(w, p.camera);
            w.end_object();
        }
        w.key("vertices").begin_array();
        for (const TracedVertex& v : p.vertices) json_vertex(w, v);
        w.end_array().field("contribution", p.contribution);
        w.key("wavelengths").begin_array();
        for (float l : p.lambda) w.value(l);
        w.end_array().key("wavelength_pdfs").begin_array();
        for (float l : p.lambda_pdf) w.value(l);
        w.end_array();
        if (p.visible_point) {
            w.key("visible_point");
            json_visible_point(w, *p.visible_point);
        }
        w.end_object();
    }
    w.end_array().end_object();
    return w.str() + "\n";
}

void report_trace(const render::PathRecorder& trace, const TraceHeader& header,
                  const std::string& json_path) {
    const std::string text = trace_text(trace, header);
    std::fwrite(text.data(), 1, text.size(), stdout);
    std::fflush(stdout);
    if (json_path.empty()) return;
    const std::string json = trace_json(trace, header);
    io::atomic_write(json_path, [&](const std::string& temp) {
        std::ofstream f(temp, std::ios::binary);
        f.write(json.data(), std::streamsize(json.size()));
        if (!f) throw InputError("write failed");
    });
}

}  // namespace phos::app
