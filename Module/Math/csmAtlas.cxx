// SPDX-License-Identifier: BSD-3-Clause
// The atlas one light's cascades share and each cascade's error on its tile (see csmAtlas.h).
#include "csmAtlas.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace csm
{
namespace
{
/// max(M_s / width, M_t / height) for the map as it is turned now, or turned once more.
double errorAsTurned(const Cascade& cascade, const MapSize& map, bool turnOnceMore = false)
{
  const glm::dvec2 m = mapAxisAliasing(cascade);
  return turnOnceMore ? std::max(m.y / map.width, m.x / map.height)
                      : std::max(m.x / map.width, m.y / map.height);
}
} // namespace

AtlasGrid atlasLayout(int mostCascades, int resolution, int maximumSide)
{
  AtlasGrid atlas;
  if (mostCascades < 1 || resolution < 1)
  {
    return atlas;
  }
  const int maps = std::min(mostCascades, kAtlasFullMaps);
  const int side = static_cast<int>(std::lround(std::sqrt(double(maps))));
  atlas.columns = side * side == maps ? side : maps;
  atlas.rows = side * side == maps ? side : 1;
  int tile = resolution;
  if (maximumSide > 0)
  {
    tile = std::max(1, std::min(tile, maximumSide / std::max(atlas.columns, atlas.rows)));
  }
  atlas.tile = MapSize(tile);
  return atlas;
}

AtlasGrid atlasGrid(int count, const AtlasGrid& atlas)
{
  AtlasGrid grid;
  if (count < 1 || atlas.tile.width < 1 || atlas.tile.height < 1)
  {
    return grid;
  }
  const long long width = static_cast<long long>(atlas.columns) * atlas.tile.width;
  const long long height = static_cast<long long>(atlas.rows) * atlas.tile.height;
  auto better = [](const MapSize& a, const MapSize& b)
  {
    const int shortA = std::min(a.width, a.height), shortB = std::min(b.width, b.height);
    return shortA != shortB
      ? shortA > shortB
      : static_cast<long long>(a.width) * a.height > static_cast<long long>(b.width) * b.height;
  };
  for (int columns = 1; columns <= count; ++columns)
  {
    const int rows = (count + columns - 1) / columns;
    const MapSize tile(static_cast<int>(std::min<long long>(width / columns, atlas.tile.width)),
      static_cast<int>(std::min<long long>(height / rows, atlas.tile.height)));
    if (better(tile, grid.tile))
    {
      grid.columns = columns;
      grid.rows = rows;
      grid.tile = tile;
    }
  }
  return grid;
}

AtlasGrid atlasForCount(int count, const AtlasGrid& atlas)
{
  if (count < 1 || atlas.tile.width < 1 || atlas.tile.height < 1)
  {
    return AtlasGrid();
  }
  if (count > 1)
  {
    return atlasGrid(count, atlas);
  }
  AtlasGrid one;
  one.tile = MapSize(std::min(atlas.columns * atlas.tile.width, atlas.rows * atlas.tile.height));
  return one;
}

MapSize resolutionCeilingForCount(int count, int mostCascades, int resolution)
{
  return atlasForCount(count, atlasLayout(std::max(mostCascades, count), resolution)).tile;
}

CascadeCeilings ceilingsForCount(int count, int mostCascades, int resolution)
{
  CascadeCeilings ceilings(resolutionCeilingForCount(count, mostCascades, resolution));
  ceilings.following.width = std::min(ceilings.following.width, std::max(resolution, 0));
  ceilings.following.height = std::min(ceilings.following.height, std::max(resolution, 0));
  return ceilings;
}

std::array<int, 4> AtlasPlan::tile(int i) const
{
  const int columns = std::max(this->tiles.columns, 1);
  return { (i % columns) * this->tiles.tile.width, (i / columns) * this->tiles.tile.height,
    this->tiles.tile.width, this->tiles.tile.height };
}

AtlasPlan planAtlas(int count, int mostCascades, const AtlasLimits& limits)
{
  AtlasPlan plan;
  if (limits.resolution < 1 || limits.ceiling < 1)
  {
    return plan;
  }
  // (The texture also for no cascade: a light keeps its atlas while it has nothing to shadow.)
  const AtlasGrid budget =
    atlasLayout(std::max({ mostCascades, count, 1 }), limits.resolution, limits.maximumSide);
  plan.texture = MapSize(budget.columns * budget.tile.width, budget.rows * budget.tile.height);
  if (count < 1)
  {
    return plan;
  }
  plan.tiles = atlasForCount(count, budget);
  plan.shrunk = budget.tile.width < limits.resolution;
  plan.ceilings =
    ceilingsForCount(count, mostCascades, std::min(limits.ceiling, limits.resolution));
  for (MapSize* most : { &plan.ceilings.sceneFitted, &plan.ceilings.following })
  {
    most->width = std::min(most->width, plan.tiles.tile.width);
    most->height = std::min(most->height, plan.tiles.tile.height);
  }
  return plan;
}

glm::dvec2 mapAxisAliasing(const Cascade& cascade)
{
  return cascade.mapTurned ? glm::dvec2(cascade.Mz, cascade.Mx)
                           : glm::dvec2(cascade.Mx, cascade.Mz);
}

double predictedError(const Cascade& cascade, double imageHeight, const MapSize& map)
{
  if (map.width <= 0 || map.height <= 0)
  {
    return std::numeric_limits<double>::infinity();
  }
  return imageHeight * std::min(errorAsTurned(cascade, map), errorAsTurned(cascade, map, true));
}

double predictedError(const ShadowSetup& setup, double imageHeight, const CascadeCeilings& maps)
{
  if (setup.cascades.empty())
  {
    return std::numeric_limits<double>::infinity();
  }
  double worst = 0.0;
  for (const Cascade& c : setup.cascades)
  {
    worst = std::max(worst, predictedError(c, imageHeight, maps.of(c)));
  }
  return worst;
}

void orientToTile(ShadowSetup& setup, const MapSize& tile)
{
  if (tile.width <= 0 || tile.height <= 0 || tile.width == tile.height)
  {
    return;
  }
  for (Cascade& c : setup.cascades)
  {
    if (c.sceneFitted || !(errorAsTurned(c, tile, true) < errorAsTurned(c, tile)))
    {
      continue; // (a scene-fitted map keeps its axes: its matrix must not change with the view)
    }
    // New s = old t, new t = -old s (glm is column-major: m[column][row]).
    for (int column = 0; column < 4; ++column)
    {
      const double s = c.wsToClip[column][0];
      c.wsToClip[column][0] = c.wsToClip[column][1];
      c.wsToClip[column][1] = -s;
    }
    c.mapTurned = !c.mapTurned;
  }
}

} // namespace csm
