// A family's contact sheet: every member painted and framed in its own cell of one image,
// labelled with its seed.
#pragma once

#include <vector>

#include "generators/tree.h"
#include "pipeline/frame/paint_frame.h"

namespace pleinair {

struct SheetOptions {
    int width = 1920;
    int height = 1080;
    int gap = 6;  // pixels of canvas between cells
    BuildSettings build;
    RenderSettings render;
};

// `family` supplies the preset and its shaders; `trees` are its members (generate_family).
// Cells are laid out in the grid that gives the largest portrait cells. Same bytes on any
// number of threads.
Frame paint_contact_sheet(const Family& family, const std::vector<Tree>& trees,
                          const SheetOptions& options, FrameReport* report = nullptr);

// The grid for n cells in a width x height image: columns and rows.
void sheet_grid(int n, int width, int height, int& cols, int& rows);

}  // namespace pleinair
