#pragma once
// The readers of the scene file's sections, one a section, and the table
// readScene walks. Internal to scene/: the stage's front door is read_scene.h.
#include <filesystem>
#include <span>
#include <string>

#include "core/diagnostics.h"
#include "scene/scene_spec.h"
#include "scene/section.h"

namespace relief::scene {

/// What a section's reader may need beside its section.
struct SceneFile {
    const std::filesystem::path& path;  ///< the scene file: the paths it gives are relative to its folder
    const std::string& name;            ///< as diagnostics name it
    const toml::table& root;            ///< the whole document, overrides applied
    Diagnostics& diags;
};

using SectionReadFn = void (*)(Section&, const SceneFile&, SceneSpec&);

/// A [section]: its name, where its keys' locations go, and its reader. A
/// `many` section is an array of tables ([[layer]]): `locations` appends a
/// new element to the spec and gives its locations, once for each table,
/// before `read` reads the table into that element.
struct SectionReader {
    const char* name;
    KeyLocations& (*locations)(SceneSpec&);
    SectionReadFn read;
    bool many = false;
};

/// Every section, in the order they are read (and their problems reported).
std::span<const SectionReader> sectionReaders();

// The data and the geometry (read_sections.cpp).
void readSamples(Section& s, const SceneFile& f, SceneSpec& scene);
void readFrame(Section& s, const SceneFile& f, SceneSpec& scene);
void readNet(Section& s, const SceneFile& f, SceneSpec& scene);
void readSubdivision(Section& s, const SceneFile& f, SceneSpec& scene);
void readLimits(Section& s, const SceneFile& f, SceneSpec& scene);
void readGeometry(Section& s, const SceneFile& f, SceneSpec& scene);
void readRender(Section& s, const SceneFile& f, SceneSpec& scene);

// The look (read_look_sections.cpp).
void readVertical(Section& s, const SceneFile& f, SceneSpec& scene);
void readTexture(Section& s, const SceneFile& f, SceneSpec& scene);
void readLighting(Section& s, const SceneFile& f, SceneSpec& scene);
void readCamera(Section& s, const SceneFile& f, SceneSpec& scene);
void readBase(Section& s, const SceneFile& f, SceneSpec& scene);
void readWater(Section& s, const SceneFile& f, SceneSpec& scene);
void readAtmosphere(Section& s, const SceneFile& f, SceneSpec& scene);
void readOverlay(Section& s, const SceneFile& f, SceneSpec& scene);
/// A date-time key's text: a string, or TOML's own offset date-time written without quotes.
std::optional<std::string> dateTimeText(const toml::node& n);

// The film (read_animation.cpp).
void readAnimation(Section& s, const SceneFile& f, SceneSpec& scene);

// The vector layers (read_layers.cpp): one [[layer]] into scene.layers.back().
void readLayer(Section& s, const SceneFile& f, SceneSpec& scene);

}  // namespace relief::scene
