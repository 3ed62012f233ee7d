// The run and scene option tables, and the list of every table `phos render` takes (see
// render_options.h).
#include "app/lib/render_options.h"

#include <sstream>

#include "accel/device_config.h"

namespace phos::app {

using options::at_least;
using options::between;
using options::Effect;

namespace {
// Gives the option added last a one-letter name.
template <class B>
void table_short(B& b, const char* letter) {
    b.last().short_name = letter;
}
}  // namespace

const options::Choices<Quality>& quality_choices() {
    static const options::Choices<Quality> choices{
        {Quality::Draft, "draft"}, {Quality::Normal, "normal"}, {Quality::High, "high"}};
    return choices;
}

const options::Table& run_options() {
    static const options::Table table = [] {
        options::TableBuilder<RunOptions> b("Run", "output, integrator, threads and messages");
        auto& out = b.text("output", &RunOptions::output, "FILE",
                           "output image: .exr (linear float), .pfm (linear), .png / .bmp (sRGB 8-bit)");
        out.effect = Effect::None;
        out.short_name = "o";
        out.default_text =
            "the scene file's Film filename (pbrt.exr if a pbrt file names none); .scn, .scene: the scene's "
            "name with .png, beside it";
        auto& integ = b.choice("integrator", &RunOptions::integrator, integrators::integrator_choices(),
                               "rendering algorithm");
        integ.default_text = "the scene file's (pbrt: path unless it names one), else photonmap";
        b.number("threads", &RunOptions::threads, "N", between(0, 4096), "worker threads (0 = all cores)")
            .effect = Effect::None;
        b.flag("verbose", &RunOptions::verbose,
               "print statistics: rays by kind, time per phase, photon counts")
            .effect = Effect::None;
        table_short(b, "v");
        b.flag("quiet", &RunOptions::quiet, "no warnings or messages").effect = Effect::None;
        table_short(b, "q");
        auto& p = b.flag("progress", &RunOptions::progress, "draw the progress bar (--no-progress: never)",
                         true, "no-progress");
        p.effect = Effect::None;
        p.default_text = "a bar on a terminal, a line every 10 % otherwise";
        b.number("exposure", &RunOptions::exposure, "STOPS", between(-64, 64),
                 "exposure in stops for .png/.bmp output")
            .effect = Effect::None;
        auto& q =
            b.choice("quality", &RunOptions::quality, quality_choices(),
                     "budget preset: samples per pixel, photon-map budgets, final-gather rays and photons "
                     "per iteration together (draft: spp 4, 50k/25k photons, 4 gather rays, 50k per "
                     "iteration; normal: the defaults; high: spp 64, 1M/500k photons, 16 gather rays, 1M "
                     "per iteration); options given explicitly or by the scene file win");
        q.effect = Effect::None;  // what it sets is recorded option by option
        b.flag("strict", &RunOptions::strict, "pbrt: unused scene parameters are errors").effect =
            Effect::None;
        auto& mem =
            b.number("max-memory", &RunOptions::max_memory, "GB", at_least(0),
                     "refuse a render whose estimated peak memory exceeds this many GB (1e9 bytes; 0 = "
                     "the memory available: free memory, cgroup and RLIMIT_AS limits)");
        mem.effect = Effect::None;
        mem.default_text = "0 (the memory available)";
        b.flag("preview", &RunOptions::preview,
               "show the image in a window as it converges (keys: + - exposure, l layer, s save, q stop)")
            .effect = Effect::None;
        b.flag("preview-hold", &RunOptions::preview_hold,
               "keep the --preview window open after the render until it is closed")
            .effect = Effect::None;
        auto& shot = b.text("preview-screenshot", &RunOptions::preview_screenshot, "FILE",
                            "write the --preview window's pixels to FILE when it closes (docs, tests)");
        shot.effect = Effect::None;
        shot.default_text = "none";
        auto& tev =
            b.text("tev", &RunOptions::tev, "HOST:PORT",
                   "stream the image to a running tev viewer (alone: " + std::string(kTevDefault) + ")");
        tev.effect = Effect::None;
        tev.default_text = "none";
        // --trace-pixel / --trace-json (app/lib/trace_output.h; the range against the image is
        // checked once its size is known).
        auto& trace = b.custom(
            "trace-pixel", "X Y", 2,
            "print every camera sample of pixel (X, Y) vertex by vertex to stdout: events, directions, "
            "throughput, light samples, photon lookups (ppm/sppm: visible points and gathered photons)",
            [](RunOptions& o, const std::vector<std::string>& v) {
                const long long x = options::parse_integer(v.at(0)), y = options::parse_integer(v.at(1));
                options::TableBuilder<RunOptions>::check_range(double(x), between(0, 65535));
                options::TableBuilder<RunOptions>::check_range(double(y), between(0, 65535));
                o.trace_x = int(x);
                o.trace_y = int(y);
            },
            [](const RunOptions& o) {
                return o.trace_x < 0 ? std::string("none")
                                     : std::to_string(o.trace_x) + " " + std::to_string(o.trace_y);
            });
        trace.effect = Effect::None;
        trace.default_text = "none";
        auto& trace_json = b.text("trace-json", &RunOptions::trace_json, "FILE",
                                  "also write the --trace-pixel record as JSON to FILE");
        trace_json.effect = Effect::None;
        trace_json.default_text = "none";
        return b.build();
    }();
    return table;
}

const options::Table& scene_options() {
    static const options::Table table = [] {
        options::TableBuilder<SceneOptions> b("Scene", "how the scene file is read and shaded");
        b.flag("schlick", &SceneOptions::schlick, "Schlick's approximation instead of exact Fresnel");
        b.flag("legacy-attenuation", &SceneOptions::legacy_attenuation,
               ".scn: honour (ca, la, qa) light attenuation in direct light");
        b.flag("emission-lights", &SceneOptions::emission_lights,
               ".scn: surfaces with emission e are area lights, on both sides (they light the scene and emit "
               "photons); --no-emission-lights: their glow is only seen, as in the seed renderer",
               true, "no-emission-lights");
        b.flag("real", &SceneOptions::real,
               ".scn: the seed's -real (scale lobes so kd + ks + kt <= 1), which phos always does; see "
               "--raw-materials")
            .effect = Effect::None;
        b.flag(
            "raw-materials", &SceneOptions::raw_materials,
            ".scn: keep materials with kd + ks + kt > 1 as written (they create light; by default each such "
            "channel is scaled to sum to 1, with a warning)");
        b.flag(
            "no-default-lights", &SceneOptions::no_default_lights,
            ".scn: a scene without lights gets none (by default it gets the seed renderer's two directional "
            "lights, with a warning)");
        auto& embree = b.custom(
            "embree-config", "KEY=VALUE,...", 1,
            "Embree's device configuration: isa=I or max_isa=I (sse2, sse4.2, avx, avx2, avx512) picks its "
            "kernels, frequency_level=simd128|simd256|simd512 how wide they may go, also hugepages=0|1 and "
            "verbose=0..3. Kernels of different widths can differ in a hit's last bits (and so the image): a "
            "fixed isa takes that difference between machines away",
            [](SceneOptions& o, const std::vector<std::string>& v) {
                if (const std::string e = accel::embree_config_error(v.at(0)); !e.empty())
                    throw options::ValueError(e);
                o.embree_config = v.at(0);
            },
            [](const SceneOptions& o) { return o.embree_config; });
        embree.default_text = "Embree's own choice for this CPU";
        // Not part of a checkpoint's identity: without it the kernels already follow the machine,
        // and a render may go on elsewhere (the images differ in last bits at most).
        embree.effect = Effect::None;
        return b.build();
    }();
    return table;
}

const std::vector<std::pair<std::string, std::string>>& quality_preset(Quality quality) {
    static const std::vector<std::pair<std::string, std::string>> draft{
        {"spp", "4"},          {"global", "50000"},  {"caustic", "25000"},
        {"indirect", "50000"}, {"gather-rays", "4"}, {"photons-per-iter", "50000"}};
    static const std::vector<std::pair<std::string, std::string>> normal{};
    static const std::vector<std::pair<std::string, std::string>> high{
        {"spp", "64"},           {"global", "1000000"}, {"caustic", "500000"},
        {"indirect", "1000000"}, {"gather-rays", "16"}, {"photons-per-iter", "1000000"}};
    return quality == Quality::Draft ? draft : quality == Quality::High ? high : normal;
}

std::vector<BoundTable> RenderCommand::tables() {
    return {{&run_options(), &run},
            {&render::image_options(), &render},
            {&render::sampling_options(), &render},
            {&integrators::transport_options(), &render},
            {&scene_options(), &scene},
            {&integrators::photon_map_options(), &photon_map},
            {&integrators::progressive_options(), &progressive},
            {&render::budget_options(), &budget}};
}

std::vector<const options::Table*> all_tables() {
    RenderCommand rc;
    std::vector<const options::Table*> out;
    for (const BoundTable& b : rc.tables()) out.push_back(b.table);
    return out;
}

std::string options_markdown() {
    std::ostringstream md;
    md << "# phos render: every option\n\n"
       << "Generated by `phos options --markdown` from the option tables in the source (the same tables\n"
       << "that build the command line, `--help`, validation, checkpoints and pbrt `Integrator`\n"
       << "parameters); do not edit by hand. \"Effect\": *image* options change the rendered image and are\n"
       << "part of a checkpoint's identity, *budget* options change how much work is done, *none* change\n"
       << "neither. The seed renderer's single-dash spellings (`-aa`, `-resolution`, `-real`...) are\n"
       << "accepted for every long option.\n";
    for (const options::Table* t : all_tables()) {
        md << "\n## " << t->title << "\n\n" << t->about << ".\n\n";
        md << "| option | default | values | effect | pbrt | meaning |\n| --- | --- | --- | --- | --- | --- "
              "|\n";
        for (const options::Option& o : t->options) {
            if (o.hidden) continue;
            std::string names = "`--" + o.name + (o.value_name.empty() ? "" : " " + o.value_name) + "`";
            for (const auto& a : o.aliases) names += ", `--" + a + "`";
            if (!o.negation.empty()) names += ", `--" + o.negation + "`";
            const char* effect = o.effect == Effect::Image    ? "image"
                                 : o.effect == Effect::Budget ? "budget"
                                                              : "none";
            std::string help = o.help;
            if (!o.applies_to.empty())
                help = "(" + integrators::integrator_names(o.applies_to, " ") + ") " + help;
            std::string def = t->default_text(o);
            if (def.empty()) def = "none";
            auto cell = [](std::string text) {  // a '|' would end the table cell
                for (size_t at = 0; (at = text.find('|', at)) != std::string::npos; at += 2)
                    text.insert(at, "\\");
                return text;
            };
            md << "| " << names << " | " << cell(def) << " | " << cell(o.flag ? "" : o.range_text) << " | "
               << effect << " | " << (o.pbrt.empty() ? "" : "`" + o.pbrt + "`") << " | " << cell(help)
               << " |\n";
        }
    }
    return md.str();
}

}  // namespace phos::app
