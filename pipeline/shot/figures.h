// A scene's figures (staffage, issue 52 §6) as strokes of the landscape: each figure's touches
// as a particle file's would be, with their own widths and colours (build_landscape adds a
// chunk per figure).
#pragma once

#include "pipeline/input/particle_files.h"
#include "pipeline/input/scene.h"

namespace pleinair {

// One figure's touches in the world, in its material, each in its part's colour (linear) and
// its own width, labelled by (seed, index), never fading. Pure in the figure.
ImportedParticles figure_particles(const FigureDesc& figure, const glm::vec3& sun_direction);

}  // namespace pleinair
