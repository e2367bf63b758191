// The thick wall (wall_law: thick; docs/MODEL.md "The thick wall"): an incompressible sphere of inner radius A = L/2
// and outer radius B = A + t, inflated by the pressure on its inner face. Internal header of src/core: the membrane
// wall's functions (membrane_wall.hpp) dispatch here when MembraneWall::thick is set.
#pragma once

#include "pneumatic_finger/core/membrane_wall.hpp"

namespace pneumatic_finger {

/// Fills @p wall's gent_root_x, gent_root_sqrt and gent_weight from its locking_jm (> 0) and locking_stretch_excess.
void setThickGentRoots(MembraneWall& wall);

/// The outer face's stretch excess delta_b = lambda_b - 1 for the inner one's @p delta: incompressibility keeps the
/// wall's volume, b^3 - a^3 = B^3 - A^3, so lambda_b^3 - 1 = (A/B)^3 (lambda_a^3 - 1); cancellation-free.
double thickOuterStretchExcess(const MembraneWall& wall, double delta);

/// The pressure (Pa) at inner stretch excess @p delta: P = 2 mu int_{lambda_b}^{lambda_a} (lambda^-2 + lambda^-5)
/// G(lambda) dlambda, G the Gent factor, in closed form (partial fractions for Gent); +inf at or past the lock.
double thickGaugeForStretchExcess(const MembraneWall& wall, double delta);

/// dP/ddelta at @p delta (> 0), by Leibniz's rule: 2 mu (f(lambda_a) - f(lambda_b) (A/B)^3 lambda_a^2/lambda_b^2),
/// f = (lambda^-2 + lambda^-5) G: no integral.
double thickGaugeSlope(const MembraneWall& wall, double delta);

/// Both at once (the Newton steps take them together): the outer face's stretch is computed once.
void thickGaugeAndSlope(const MembraneWall& wall, double delta, double& gauge_pa, double& slope_pa);

}  // namespace pneumatic_finger
