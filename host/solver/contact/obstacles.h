// Obstacles as the kernels see them: each snh::Obstacle placed at a load
// parameter and written as a record of kernels/contact/obstacle.h.
#pragma once

#include <vector>

#include "snh/simulation.h"

namespace snh::solver {

// Throws snh::Error naming obstacle k or the contact option at fault: a
// non-finite entry, a zero direction, a radius <= 0 (sphere, cylinder), a
// stiffness <= 0 with obstacles, a thickness < 0.
void validate_obstacles(const std::vector<Obstacle>& obstacles, const ContactOptions& contact);

// SNH_OBSTACLE_RECORD reals per obstacle, placed at load parameter t (its
// motion, unit normal / axis). snh::Error naming the obstacle for a motion
// that gives a non-finite placement.
std::vector<double> obstacle_records(const std::vector<Obstacle>& obstacles, double t);

// Obstacle k's friction coefficient: its own, else the contact option's.
double friction_coefficient(const Obstacle& obstacle, const ContactOptions& contact);
// Whether any obstacle has friction (the kernels then carry SNH_FRICTION).
bool has_friction(const std::vector<Obstacle>& obstacles, const ContactOptions& contact);

// SNH_FRICTION_RECORD reals per obstacle (kernels/contact/obstacle.h): its
// coefficient and the rigid map (R column-major, t) that takes the obstacle
// placed at load parameter t0 to its placement at t1.
std::vector<double> friction_records(const std::vector<Obstacle>& obstacles, const ContactOptions& contact, double t0,
                                     double t1);

}  // namespace snh::solver
