#include "subdiv/resolve.h"

#include <algorithm>

#include <fmt/format.h>

#include "core/number_format.h"
#include "core/text_distance.h"

namespace relief::subdiv {

namespace {

// The preset's family and its parameters, from the preset's own parameters.
bool resolvePreset(const scene::SchemeSpec& spec, Diagnostics& diags, std::string& familyName,
                   SchemeParams& familyParams) {
    const SourceLoc loc = spec.locs.at("subdivision.preset");
    const Preset* preset = findPreset(spec.preset);
    if (!preset) {
        std::vector<std::string> names;
        std::string list;
        for (const auto& p : presets()) {
            names.push_back(p.name);
            list += (list.empty() ? "" : ", ") + p.name;
        }
        diags.error(loc, fmt::format("unknown preset \"{}\"{}; known: {}", spec.preset,
                                     didYouMean(spec.preset, names), list));
        return false;
    }
    SchemeParams own;
    bool ok = true;
    for (const auto& [key, value] : spec.params) {
        const auto known = std::find_if(preset->params.begin(), preset->params.end(),
                                        [&name = key](const ParamSpec& s) { return s.name == name; });
        if (known == preset->params.end()) {
            diags.error(spec.locs.at("subdivision." + key),
                        fmt::format("preset \"{}\" fixes every parameter of \"{}\"{}; remove "
                                    "\"{}\" or use scheme = \"{}\" instead",
                                    spec.preset, preset->family,
                                    preset->params.empty() ? "" : " but " + preset->params[0].name,
                                    key, preset->family));
            ok = false;
        }
    }
    for (const auto& p : preset->params) {
        const auto it = spec.params.find(p.name);
        const double v = it == spec.params.end() ? p.defaultValue : it->second;
        if (!(v >= p.lo && v <= p.hi)) {
            diags.error(spec.locs.at("subdivision." + p.name),
                        fmt::format("{} = {} is outside [{}, {}] for preset \"{}\"", p.name,
                                    formatShortest(v), formatShortest(p.lo), formatShortest(p.hi),
                                    spec.preset));
            ok = false;
        }
        own[p.name] = v;
    }
    if (!ok) return false;
    familyName = preset->family;
    familyParams = preset->familyParams(own);
    return true;
}

// A family's scheme: parameter names and ranges checked, defaults filled in.
// `paramKeys` is false for a preset's parameters, which have no key of their own.
std::optional<Scheme> buildFamily(const std::string& name, const SchemeParams& params,
                                  const scene::SchemeSpec& spec, bool paramKeys,
                                  Diagnostics& diags, SchemeParams& resolved) {
    const SourceLoc nameLoc = spec.locs.at("subdivision.scheme");
    const SchemeFamily* family = findSchemeFamily(name);
    if (!family) {
        std::vector<std::string> names;
        std::string list;
        for (const auto& f : schemeFamilies()) {
            names.push_back(f.name);
            list += (list.empty() ? "" : ", ") + ("\"" + f.name + "\"");
        }
        diags.error(nameLoc, fmt::format("unknown subdivision scheme \"{}\"{}; known: {}, or "
                                         "\"mask\" with arity and mask (or a preset)",
                                         name, didYouMean(name, names), list));
        return std::nullopt;
    }
    auto locOf = [&](const std::string& key) {
        return paramKeys && spec.locs.has("subdivision." + key) ? spec.locs.at("subdivision." + key)
                                                                 : nameLoc;
    };
    std::vector<std::string> paramNames;
    for (const auto& p : family->params) paramNames.push_back(p.name);

    bool ok = true;
    for (const auto& [key, value] : params) {
        if (std::find(paramNames.begin(), paramNames.end(), key) != paramNames.end()) continue;
        std::string expected;
        for (const auto& n : paramNames) expected += (expected.empty() ? "" : ", ") + n;
        diags.error(locOf(key), fmt::format("unknown parameter \"{}\" for scheme \"{}\"{}; it takes: {}",
                                            key, name, didYouMean(key, paramNames), expected));
        ok = false;
    }
    for (const auto& p : family->params) {
        auto it = params.find(p.name);
        const double v = it == params.end() ? p.defaultValue : it->second;
        if (!(v >= p.lo && v <= p.hi)) {
            diags.error(locOf(p.name), fmt::format("{} = {} is outside [{}, {}] for scheme \"{}\" ({})",
                                                   p.name, formatShortest(v), formatShortest(p.lo),
                                                   formatShortest(p.hi), name, p.meaning));
            ok = false;
        }
        resolved[p.name] = v;
    }
    if (!ok) return std::nullopt;
    if (family->caveats)
        for (auto& w : family->caveats(resolved)) diags.warning(nameLoc, std::move(w));
    return family->build(resolved);
}

}  // namespace

std::optional<ResolvedScheme> resolveScheme(const scene::SchemeSpec& spec, Diagnostics& diags) {
    const SourceLoc nameLoc = spec.locs.at("subdivision.scheme");
    ResolvedScheme out;
    out.family = spec.name;
    SchemeParams params = spec.params;
    bool paramKeys = true;
    if (!spec.preset.empty()) {
        SchemeParams familyParams;
        if (!resolvePreset(spec, diags, out.family, familyParams)) return std::nullopt;
        if (!spec.name.empty() && spec.name != out.family) {
            diags.error(spec.locs.at("subdivision.preset"),
                        fmt::format("preset \"{}\" is a case of scheme \"{}\", not \"{}\"; name "
                                    "that scheme or leave the scheme out",
                                    spec.preset, out.family, spec.name));
            return std::nullopt;
        }
        params = familyParams;
        paramKeys = false;
    } else if (spec.name.empty()) {
        diags.error(nameLoc, "no scheme given: name a scheme (relief check --list shows them) or a preset");
        return std::nullopt;
    }
    std::optional<Scheme> scheme;
    if (out.family == "mask") {
        if (!params.empty())
            diags.error(spec.locs.at("subdivision." + params.begin()->first),
                        fmt::format("scheme = \"mask\" takes no parameter \"{}\"", params.begin()->first));
        else if (spec.mask.empty() && spec.locs.has("subdivision.mask")) {
            // written, but refused by the scene reader, which said why at the key
        } else if (spec.mask.empty() || spec.maskArity == 0)
            diags.error(nameLoc, "scheme = \"mask\" needs subdivision.arity (2 or 3) and "
                                 "subdivision.mask = [a_k, ...]");
        else
            scheme = schemeFromMask(
                spec.maskArity,
                spec.maskFirst.value_or(-(static_cast<int>(spec.mask.size()) - 1) / 2), spec.mask,
                spec.locs.at("subdivision.mask"), diags);
    } else {
        scheme = buildFamily(out.family, params, spec, paramKeys, diags, out.params);
    }
    if (!scheme || diags.hasErrors()) return std::nullopt;
    out.scheme = std::move(*scheme);
    out.report = analyzeScheme(out.scheme);
    if (out.report.smoothness < 0 && !spec.allowNonconvergent)
        diags.warning(nameLoc, fmt::format("scheme \"{}\" with these parameters is not proven to "
                                           "converge (relief check says why): the terrain will "
                                           "look rough and fractal-like; set "
                                           "subdivision.allow_nonconvergent = true if that is "
                                           "what you want",
                                           out.family));
    return out;
}

}  // namespace relief::subdiv
