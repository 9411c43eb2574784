// The headers nearly every test reads, precompiled once for the test program (tests/CMakeLists.txt):
// the standard library, GoogleTest, GLM and the project's scene and tree types. Each test file
// still includes what it uses; this only saves parsing them seventy times (CI's time, issue 51).
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>
#include <glm/matrix.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>
#include <map>
#include <memory>
#include <set>
#include <sstream>
#include <string>
#include <unordered_map>
#include <vector>

#include "generators/tree.h"
#include "pipeline/input/scene.h"
#include "pipeline/shot/shot.h"
