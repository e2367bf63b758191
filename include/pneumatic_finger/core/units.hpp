// The constants and unit conversions the package uses, defined once.
#pragma once

namespace pneumatic_finger {

/// pi to double precision (M_PI is POSIX, not C++17).
constexpr double kPi = 3.14159265358979323846;

/// Degrees per radian, for the tools' human-readable tables.
constexpr double kDegPerRad = 180.0 / kPi;

/// One kilogram-force per square centimetre in pascals (exact by definition: 9.80665 N / 1e-4 m^2). The paper and
/// its Table 1 give pressures in kg/cm^2 gauge.
constexpr double kPaPerKgfPerCm2 = 98066.5;

/// One litre per minute in cubic metres per second (flow meters and regulators are rated in L/min).
constexpr double kM3PerSPerLitrePerMinute = 1e-3 / 60.0;

/// Standard atmosphere (Pa), the default P_o.
constexpr double kStandardAtmospherePa = 101325.0;

}  // namespace pneumatic_finger
