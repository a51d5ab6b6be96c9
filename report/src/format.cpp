// The report's tables: the value columns, and the CSV and JSON files.
#include "deepgi/report.hpp"

#include <fmt/format.h>

#include <cmath>

namespace deepgi::report {

// The frame's passes the report times, by the names the frame's timer gives
// them; each becomes the column "<pass>_ms". A name the frame does not time
// stops the report where a row is filled rather than leaving a column empty.
const std::vector<std::string>& timed_passes() {
    static const std::vector<std::string> passes = {"sao", "blur", "radiosity"};
    return passes;
}

const std::vector<std::string>& value_columns() {
    static const std::vector<std::string> columns = [] {
        // ao_slices and ao_steps: the slice estimators' cost (empty for the others).
        // temporal_offset and rotation_seed: the repeat's realisation of the
        // per-frame and the per-pixel rotation (repeat_offset, repeat_rotation_seed).
        std::vector<std::string> names = {"discrepancy",   "turns",     "temporal_offset",
                                          "rotation_seed", "ao_slices", "ao_steps"};
        for (const auto& pass : timed_passes()) names.push_back(pass + "_ms");
        for (const char* name : {
                 "conv_raw_mae",
                 "conv_raw_rmse",
                 "conv_blur_mae",
                 "conv_blur_rmse",
                 "ref_raw_mae",
                 "ref_raw_rmse",
                 "ref_raw_bias",
                 "ref_blur_mae",
                 "ref_blur_rmse",
                 "ref_blur_bias",
                 "ref_temporal_mae",
                 "ref_temporal_rmse",
                 "ref_temporal_bias",
                 "ref_accum_mae",
                 "ref_accum_rmse",
                 "ref_accum_bias",
                 "ref_pixels",
                 "ref_open_pixels",
                 "ref_open_raw_below",
                 "ref_open_blur_below",
                 "ref_open_accum_below",
                 "ref_open_core_raw_below",
                 "ref_open_core_blur_below",
                 "ref_open_core_accum_below",
                 "rad_conv_raw_rel_mae",
                 "rad_conv_raw_rel_rmse",
                 "rad_conv_blur_rel_mae",
                 "rad_conv_blur_rel_rmse",
                 "rad_ref_raw_rel_mae",
                 "rad_ref_raw_rel_rmse",
                 "rad_ref_raw_rel_bias",
                 "rad_ref_blur_rel_mae",
                 "rad_ref_blur_rel_rmse",
                 "rad_ref_blur_rel_bias",
                 "rad_ref_temporal_rel_mae",
                 "rad_ref_temporal_rel_rmse",
                 "rad_ref_temporal_rel_bias",
                 "rad_ref_accum_rel_mae",
                 "rad_ref_accum_rel_rmse",
                 "rad_ref_accum_rel_bias",
                 "rad_vis_blur_rel_mae",
                 "rad_vis_blur_rel_rmse",
                 "rad_vis_blur_rel_bias",
                 "rad_vis_accum_rel_mae",
                 "rad_vis_accum_rel_rmse",
                 "rad_vis_accum_rel_bias",
                 "rad_still_frames",
                 "rad_ref_still_rel_mae",
                 "rad_ref_still_rel_rmse",
                 "rad_ref_still_rel_bias",
                 "rad_vis_still_rel_mae",
                 "rad_vis_still_rel_rmse",
                 "rad_vis_still_rel_bias",
                 "rad_unheld_share",
                 "ao_radius",
                 "radiosity_radius",
             })
            names.push_back(name);
        return names;
    }();
    return columns;
}

std::optional<double> Row::get(std::string_view column) const {
    for (const Value& v : values)
        if (v.column == column) return v.value;
    return std::nullopt;
}

std::string format_csv(const std::vector<Row>& rows) {
    std::string text = "scene,pattern,taps,layers,ao_method,device";
    for (const std::string& column : value_columns()) text += "," + column;
    text += "\n";
    for (const Row& row : rows) {
        text += fmt::format("{},{},{},{},{},{}", csv_field(row.scene), csv_field(row.pattern),
                            row.taps, row.layers, csv_field(row.ao_method), csv_field(row.device));
        for (const std::string& column : value_columns()) {
            const auto value = row.get(column);
            text += value ? fmt::format(",{}", *value) : ",";
        }
        text += "\n";
    }
    return text;
}

namespace {
std::string json_string(std::string_view text) {
    std::string out = "\"";
    for (char c : text) {
        if (c == '"' || c == '\\') {
            out += '\\';
            out += c;
        } else if (static_cast<unsigned char>(c) < 0x20) {
            out += fmt::format("\\u{:04x}", int(c));
        } else {
            out += c;
        }
    }
    return out + "\"";
}
}  // namespace

namespace {
std::string json_number(double value) {
    return std::isfinite(value) ? fmt::format("{}", value) : "null";
}
}  // namespace

std::string format_json(const std::vector<Row>& rows, const ReportInfo& info,
                        const std::vector<StabilityRow>& stability,
                        const std::vector<spiral_float::Choice>& float_choices) {
    std::string text = "{\"info\":{";
    text += fmt::format(
        "\"renderer\":{},\"vendor\":{},\"timing\":{},\"width\":{},\"height\":{},"
        "\"guard\":{},\"rays\":{},\"converged_taps\":{},\"warmup\":{},\"frames\":{},"
        "\"image_pattern\":{},\"image_taps\":{},\"repeats\":{},\"lengths\":{},"
        "\"radiosity_frames\":{},\"radiosity_taps\":{},\"seconds\":{}",
        json_string(info.renderer), json_string(info.vendor),
        json_string(info.cpu_clock ? "CPU clock around glFinish" : "GL timer queries"), info.width,
        info.height, info.guard, info.rays, info.converged_taps, info.warmup, info.frames,
        json_string(info.image_pattern), info.image_taps, info.repeats, json_string(info.lengths),
        info.radiosity_frames, info.radiosity_taps, info.seconds);
    text += "},\n\"rows\":[\n";
    for (std::size_t r = 0; r < rows.size(); ++r) {
        const Row& row = rows[r];
        text += fmt::format(
            "{{\"scene\":{},\"pattern\":{},\"taps\":{},\"layers\":{},\"ao_method\":{},"
            "\"device\":{}",
            json_string(row.scene), json_string(row.pattern), row.taps, row.layers,
            json_string(row.ao_method), json_string(row.device));
        for (const std::string& column : value_columns()) {
            const auto value = row.get(column);
            text += fmt::format(",\"{}\":{}", column, value ? json_number(*value) : "null");
        }
        text += r + 1 < rows.size() ? "},\n" : "}\n";
    }
    text += "],\n\"stability\":[\n";
    for (std::size_t r = 0; r < stability.size(); ++r) {
        const StabilityRow& row = stability[r];
        text += fmt::format(
            "{{\"ao_method\":{},\"case\":{},\"quantity\":{},\"value\":{},\"test\":{},"
            "\"tolerance\":{},\"pass\":{}}}{}",
            json_string(row.ao_method), json_string(row.case_name), json_string(row.quantity),
            json_number(row.value), json_string(row.test), json_number(row.tolerance),
            row.pass ? "true" : "false", r + 1 < stability.size() ? ",\n" : "\n");
    }
    // Only the n where the choices differ; float_vs_exact.csv has every n.
    int differing = 0, larger_k = 0;
    std::string listed;
    for (const spiral_float::Choice& c : float_choices) {
        if (!c.differs()) continue;
        ++differing;
        larger_k += !c.tie();
        listed += fmt::format(
            "{}{{\"n\":{},\"exact_tau\":{},\"exact_K\":{},\"float_tau\":{},"
            "\"float_tau_exact_K\":{},\"denominator\":{}}}",
            listed.empty() ? "" : ",\n", c.n, c.exact_tau, c.exact_k, c.float_tau,
            c.float_tau_exact_k, c.denominator);
    }
    text += fmt::format(
        "],\n\"float_vs_exact\":{{\"max_n\":{},\"differing\":{},\"larger_K\":{},"
        "\"rows\":[\n{}{}]}}}}\n",
        float_choices.size(), differing, larger_k, listed, listed.empty() ? "" : "\n");
    return text;
}

}  // namespace deepgi::report
