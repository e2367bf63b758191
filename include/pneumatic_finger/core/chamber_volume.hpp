// The chambers' volume and the volume a supply must push in (docs/MODEL.md, "Volume").
//
// Each wall law says how its chamber grows with its state:
//  - the paper law (stage 3): each of a chamber's two walls bulges into half an ellipse of semi-axes L/2 and L/2 + h,
//    extruded across the chamber's width e, so the chamber grows by 2 * e * (pi/4) L h = (pi/2) L e h;
//  - the membrane law: the chamber is a membrane stretched by lambda in every direction within it, so every length of
//    it grows by lambda and its volume by lambda^3: V_o (lambda^3 - 1), V_o = L d e, with
//    lambda^3 - 1 = delta (3 + 3 delta + delta^2) (no cancellation near rest).
// The supply pushes in the chambers' growth and, where the fluid is a gas, what compressing the gas at rest in the
// drive (cylinder, tube and chambers: dead_volume_m3, V_g, at P_o) to P takes, isothermally: V_g P / (P_o + P).
#pragma once

namespace pneumatic_finger {

/// The membrane chamber's growth per unit of rest volume, lambda^3 - 1, at stretch excess @p delta (>= 0).
inline double membraneVolumeGrowthFactor(double delta) { return delta * (3.0 + delta * (3.0 + delta)); }

/// d(lambda^3 - 1)/d delta = 3 lambda^2.
inline double membraneVolumeGrowthSlope(double delta) { return 3.0 * (1.0 + delta) * (1.0 + delta); }

/// The paper law's chamber growth per metre of bulge, (pi/2) L e (m^2), for chamber height @p chamber_height_m (L) and
/// width @p chamber_width_m (e).
double paperVolumePerBulgeM2(double chamber_height_m, double chamber_width_m);

/// The volume (m^3, at the supply's side) that compressing @p dead_volume_m3 of gas from @p atmospheric_pa to the
/// gauge pressure @p gauge_pa takes, isothermally: V_g P / (P_o + P). 0 for an incompressible fluid (V_g = 0);
/// negative for a vacuum (the gas expands).
double deadGasUptakeM3(double dead_volume_m3, double gauge_pa, double atmospheric_pa);

}  // namespace pneumatic_finger
