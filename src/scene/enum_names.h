#pragma once
// The names the scene file gives each enum's values: one table an enum, read
// by the scene reader (the choices it accepts, and its "did you mean"), and
// written by the .pov header, the sidecar and the stages' messages. A value
// is a row, as a scheme is: adding one is adding its row here.
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "scene/scene_spec.h"

namespace relief::scene {

template <class E>
struct NameRow {
    E value;
    const char* name;
};

/// Specialised for each enum the scene names: `rows`, in the order the
/// reader's messages list them.
template <class E>
struct EnumNames;

template <>
struct EnumNames<FrameKind> {
    static constexpr NameRow<FrameKind> rows[] = {
        {FrameKind::Utm, "utm"}, {FrameKind::Local, "local"}, {FrameKind::Raster, "raster"}};
};
template <>
struct EnumNames<Gridding> {
    static constexpr NameRow<Gridding> rows[] = {
        {Gridding::Linear, "linear"}, {Gridding::InverseDistance, "invdist"}, {Gridding::Nearest, "nearest"},
        {Gridding::Fit, "fit"}};
};
template <>
struct EnumNames<Unsupported> {
    static constexpr NameRow<Unsupported> rows[] = {
        {Unsupported::Show, "show"}, {Unsupported::Fade, "fade"}, {Unsupported::Mask, "mask"}};
};
template <>
struct EnumNames<Projection> {
    static constexpr NameRow<Projection> rows[] = {{Projection::Perspective, "perspective"},
                                                   {Projection::Orthographic, "orthographic"},
                                                   {Projection::Panoramic, "panoramic"},
                                                   {Projection::Spherical, "spherical"}};
};
template <>
struct EnumNames<Resample> {
    static constexpr NameRow<Resample> rows[] = {{Resample::Bilinear, "bilinear"},
                                                 {Resample::Cubic, "cubic"},
                                                 {Resample::Average, "average"},
                                                 {Resample::Nearest, "nearest"}};
};
template <>
struct EnumNames<NodataPolicy> {
    static constexpr NameRow<NodataPolicy> rows[] = {
        {NodataPolicy::Mask, "mask"}, {NodataPolicy::Fill, "fill"}, {NodataPolicy::Error, "error"}};
};
/// texture.mode names the first three; Image is what texture.image chooses.
template <>
struct EnumNames<TextureSpec::Colouring> {
    static constexpr NameRow<TextureSpec::Colouring> rows[] = {{TextureSpec::Colouring::Elevation, "elevation"},
                                                               {TextureSpec::Colouring::Slope, "slope"},
                                                               {TextureSpec::Colouring::Blend, "blend"},
                                                               {TextureSpec::Colouring::Image, "image"}};
};
template <>
struct EnumNames<GeometryKind> {
    static constexpr NameRow<GeometryKind> rows[] = {{GeometryKind::Auto, "auto"},
                                                     {GeometryKind::Mesh2, "mesh2"},
                                                     {GeometryKind::Adaptive, "adaptive"},
                                                     {GeometryKind::HeightField, "height_field"}};
};
template <>
struct EnumNames<CameraPath> {
    static constexpr NameRow<CameraPath> rows[] = {
        {CameraPath::Still, "still"}, {CameraPath::Orbit, "orbit"}, {CameraPath::Flyover, "flyover"}};
};
template <>
struct EnumNames<MarkerKind> {
    static constexpr NameRow<MarkerKind> rows[] = {
        {MarkerKind::Pin, "pin"}, {MarkerKind::Dot, "dot"}, {MarkerKind::Flag, "flag"}, {MarkerKind::None, "none"}};
};
template <>
struct EnumNames<Quality> {
    static constexpr NameRow<Quality> rows[] = {
        {Quality::Draft, "draft"}, {Quality::Report, "report"}, {Quality::High, "high"}};
};
/// texture.mode's choices: the ramp's colourings (an image is texture.image's).
inline constexpr NameRow<TextureSpec::Colouring> kTextureModeNames[] = {
    {TextureSpec::Colouring::Elevation, "elevation"},
    {TextureSpec::Colouring::Slope, "slope"},
    {TextureSpec::Colouring::Blend, "blend"}};

/// The name of `value` in the scene file.
template <class E>
constexpr const char* nameOf(E value) {
    for (const auto& row : EnumNames<E>::rows)
        if (row.value == value) return row.name;
    return "?";  // a value with no row (EnumNames.EveryValueHasOneName)
}

/// The value named `name` among `rows` (all of E's by default).
template <class E>
std::optional<E> valueNamed(std::string_view name, std::span<const NameRow<E>> rows = EnumNames<E>::rows) {
    for (const auto& row : rows)
        if (name == row.name) return row.value;
    return std::nullopt;
}

/// The names among `rows`, in order: the choices a key offers.
template <class E>
std::vector<std::string> namesOf(std::span<const NameRow<E>> rows = EnumNames<E>::rows) {
    std::vector<std::string> names;
    for (const auto& row : rows) names.emplace_back(row.name);
    return names;
}

}  // namespace relief::scene
