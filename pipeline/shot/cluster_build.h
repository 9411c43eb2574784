// Building a shot's particle clusters (particle_clusters.h): each item's particles grouped by
// place, a tree's leaves and bark also by the distance value they fade out at.
#pragma once

#include <vector>

#include "pipeline/shot/particle_clusters.h"
#include "pipeline/shot/particle_input.h"

namespace pleinair {

// One per item of the shot (trees, then surface chunks), in parallel; the result does not
// depend on threads.
std::vector<ItemClusters> build_clusters(const ParticleSource& shot);

}  // namespace pleinair
