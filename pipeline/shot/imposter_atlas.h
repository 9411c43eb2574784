// The texture atlas of graftal imposters (file 002, figure 5.9.1), drawn once per shot from an
// imposter description's sources: graftal descriptions drawn face on, or a designer's image cut
// into cells; levels halved cell by cell.
#pragma once

#include <vector>

#include "pipeline/input/imposter_desc.h"

namespace pleinair {

// The texture atlas (file 002, figure 5.9.1): `rows` types of graftal imposter, `columns`
// variations of each, every cell the same size. Premultiplied, and in the paper's key: red is
// 1 inside a graftal (where the surface's colour shows), green and blue carry the outline's
// colour (red 0), alpha its coverage. Levels halve down to a cell of 1 pixel, so a small
// imposter reads an image its own size (no shimmer as it shrinks).
struct ImposterAtlas {
    int rows = 1, columns = 1;
    int cell_w = 1, cell_h = 1;         // of level 0
    std::vector<ImposterImage> levels;  // [0] full size
};

// An atlas drawn from graftal descriptions (the "atlas of graftal images"): row r from
// descriptions[r], column c its example c mod count, varied by the description's ranges from a
// fixed seed, seen face on, fills keyed red and outlines in (0, g, b).
ImposterAtlas atlas_from_graftals(const std::vector<GraftalDesc>& descriptions, int columns,
                                  int cell_px);
// An atlas from a designer's image in the paper's format (straight alpha), cut into cells.
ImposterAtlas atlas_from_image(const ImposterImage& image, int rows, int columns);

// The atlas a description names, from its checked sources.
ImposterAtlas imposter_atlas(const ImposterDesc& desc);

}  // namespace pleinair
