// What a settings change costs each pass: the settings rows' effects, by
// owner (runtime/src/settings_rows.cpp), unless the pass says more itself.
#include "deepgi/settings.hpp"
#include "pass.hpp"

#include <fmt/format.h>

namespace deepgi {

SettingsChange rows_settings_change(const RenderSettings& before, const RenderSettings& after,
                                    const std::function<bool(std::string_view owner)>& owns) {
    SettingsChange change;
    for (const NumericSetting& row : numeric_settings()) {
        if (row.effect == SettingEffect::none || !owns(row.owner) ||
            row.get(after) == row.get(before))
            continue;
        change.reallocate = change.reallocate || row.effect == SettingEffect::reallocate;
        if (row.effect == SettingEffect::drop_history && change.drop_history.empty())
            change.drop_history =
                fmt::format("{} {} changed to {}", row.group, row.label, row.get(after));
    }
    return change;
}

SettingsChange Pass::settings_change(const RenderSettings& before,
                                     const RenderSettings& after) const {
    return rows_settings_change(before, after,
                                [this](std::string_view owner) { return owner == name(); });
}

}  // namespace deepgi
