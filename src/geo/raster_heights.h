#pragma once
// Inside geo: a DEM's heights once warped onto the net (row 0 north, as the
// warper writes them): their unit, their range, the nodes without data
// (masked or filled, as [samples] nodata says), and the net's nodes.
#include <vector>

#include "core/diagnostics.h"
#include "geo/normalize.h"
#include "geo/raster_source.h"
#include "scene/scene_spec.h"

namespace relief::geo {

/// The warper's value at a node without data; any value above half of it is a height.
inline constexpr double kNetNoData = -1.0e30;
inline bool hasData(double z) { return z > kNetNoData * 0.5; }

/// Metres per unit of the band's values (samples.vertical_unit, else the
/// band's own unit); 1, with a warning, for a unit that is not a length relief knows.
double metresPerBandUnit(const HeightBand& band, const scene::SamplesSpec& samples, Diagnostics& diags);

/// False, after an error naming the raster's cell that holds it, when a
/// node's height (`scale` z) lies beyond the Earth's (or beyond any
/// elevation's with elevations = "any").
bool checkElevations(const std::vector<double>& z, double scale, const ControlNet& net, const RasterPlace& place,
                     const HeightBand& band, const scene::SamplesSpec& samples, Diagnostics& diags);

/// The nodes without data, as samples.nodata says: an error, masked (the net's
/// `masked`, with heights filled a little way for the refiner), or filled
/// (`filledNodata`) from their neighbours by GDALFillNodata on `netBand` (the
/// warped net, whose values `z` holds and is read back from). False after an
/// error, and when no node has data.
bool resolveNodata(std::vector<double>& z, GDALRasterBandH netBand, ControlNet& net,
                   const scene::SamplesSpec& samples, const scene::NetSpec& netSpec, Diagnostics& diags);

/// The net's nodes: on its lattice, at the heights `scale` z (row 0 north); in
/// a local frame above the tangent plane, as samples are.
void setNodeHeights(ControlNet& net, const std::vector<double>& z, double scale);

}  // namespace relief::geo
