// A family's contact sheet: every member painted and framed in its own cell of one image,
// labelled with its seed.
#pragma once

#include <string>
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

// A family of `params` painted with the Corot leaf and bark shaders, as a contact sheet shows it
// (`style` other than "strokes" names a graftal for its leaves).
Family sheet_family(const std::string& name, const std::string& preset, const TreeParams& params,
                    const std::string& style = "strokes");

// The camera of a member's cell: the tree's width (any direction about the trunk) and height fit
// a width x height image with a margin, seen from slightly above its middle.
CameraParams side_camera(const BuiltTree& tree, int width, int height);

// `tree` alone in `scene` (its families, build and render settings; no terrain, sky or
// atmosphere of its own) seen by `camera`: a shot of its own, painted as a still.
Frame paint_alone(const SceneDesc& scene, const BuiltTree& tree, const CameraParams& camera,
                  bool aovs = false, FrameReport* report = nullptr);

// The grid for n cells in a width x height image: columns and rows.
void sheet_grid(int n, int width, int height, int& cols, int& rows);

}  // namespace pleinair
