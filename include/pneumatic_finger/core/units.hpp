// The constants and unit conversions the package uses, defined once.
#pragma once

namespace pneumatic_finger {

/// pi to double precision (M_PI is POSIX, not C++17).
constexpr double kPi = 3.14159265358979323846;

/// pi/2: a wall's half angle stays below it (exact: halving kPi is exact in binary).
constexpr double kHalfPi = kPi / 2;

/// Degrees per radian, for the tools' human-readable tables.
constexpr double kDegPerRad = 180.0 / kPi;

/// One kilogram-force per square centimetre in pascals (exact by definition: 9.80665 N / 1e-4 m^2). The paper and
/// its Table 1 give pressures in kg/cm^2 gauge.
constexpr double kPaPerKgfPerCm2 = 98066.5;

/// One litre per minute in cubic metres per second (flow meters and regulators are rated in L/min).
constexpr double kM3PerSPerLitrePerMinute = 1e-3 / 60.0;

/// Standard atmosphere (Pa), the default P_o.
constexpr double kStandardAtmospherePa = 101325.0;

/// The top of the model's range, 3 kg/cm^2 gauge (Pa): the node clamps higher pressures to it; the URDF's joint limits,
/// the inverse's and the gripper action's limit and the table solver's range end there.
constexpr double kModelMaxGaugePa = 3 * kPaPerKgfPerCm2;

/// The top of the validated range, 2 kg/cm^2 gauge (Pa): the paper's highest measured pressure.
constexpr double kValidatedMaxGaugePa = 2 * kPaPerKgfPerCm2;

}  // namespace pneumatic_finger
