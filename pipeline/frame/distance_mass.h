// The distance laid in as one value (issue 52 section 1): how far a touch at a view depth goes
// to the atmosphere's value, so the far bank, shore and water read as one mass when squinted at.
#pragma once

namespace pleinair {

struct Atmosphere;
struct StrokeConstants;

// The share of the way a touch at view depth `depth` goes to the distance's value: value_pull
// times a smooth step from value_near to value_far (continuous in depth, so no touch pops).
float distance_mass_amount(const Atmosphere& a, float depth);

// Linear luminance of L* (CIE 1976), the distance's value as finish_color takes it.
float luminance_of_lstar(float lstar);

// Lays the touch k, at view depth `depth`, in at the distance's value; leaves it alone when
// the atmosphere's value_pull is 0 (the same bytes as before).
void lay_in_distance_value(const Atmosphere& a, float depth, StrokeConstants& k);

}  // namespace pleinair
