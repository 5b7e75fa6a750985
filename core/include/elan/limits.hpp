// SPDX-License-Identifier: MIT
// The range of values elan supports, in SI units. A scene file or an API call outside it is
// refused (elan::SceneError / elan::Error naming the field) instead of being simulated into
// non-finite numbers. The bounds follow what Box2D and Jolt document for float engines (Box2D:
// objects of 0.1 to 10 m best, a world of a few km; Jolt: positions within about 1e4 to 1e5 m),
// widened to what users do throw at an engine (a 1 mm box on a 1 km box, 1e4 m/s shots, gravity
// of 1e4 m/s^2), and chosen so that every derived quantity stays finite in float: the
// bound each one guarantees is given with it. docs/limits.md lists them for users.
#pragma once

namespace elan::limits {

/// m: each coordinate of a body's position, and a plane's offset. A float holds 1e5 to within
/// 2^-7 m = 7.8 mm, the size of the contact slop; beyond, contacts jitter by whole ulps.
inline constexpr double kMaxPosition = 1e5;

/// m: a shape's sizes (sphere and capsule radius, box half extents, half height) and a hull's
/// half extent about its centroid along each principal axis. Below 0.1 mm a body is smaller than
/// the contact tolerances and than a float ulp at 1 km (6e-5 m); above 10 km its mass properties
/// approach the limits below (volume 8e12 m^3, inertia per unit mass 1e8 m^2).
inline constexpr double kMinSize = 1e-4;
inline constexpr double kMaxSize = 1e4;

/// kg: a dynamic body's mass, given or computed (density x volume). 1e-9 kg is a 0.1 mm sphere
/// of water; with kMinSize its inverse inertia stays below 1e18, finite in float. 1e9 kg keeps a
/// body's kinetic energy (at most 0.5 * 1e9 * (1e5)^2 + 0.5 * 1e9 * 6.7e7 * (1e5)^2 = 3.4e26 J,
/// the second term the rotation of a 10 km box) and a world's totals over 2^29 bodies (2e35)
/// below float's 3.4e38.
inline constexpr double kMinMass = 1e-9;
inline constexpr double kMaxMass = 1e9;

/// kg/m^3: a body's density. Osmium is 2.3e4 and air 1.2; the bounds leave room for scaled
/// scenes, the computed mass is checked against the mass bounds besides.
inline constexpr double kMinDensity = 1e-6;
inline constexpr double kMaxDensity = 1e9;

/// m/s and rad/s: the length of a body's linear and angular velocity when it is set. A bullet is
/// 1e3 m/s; 1e5 m/s crosses the position range in a second, and keeps m v^2 within the mass
/// bound's budget above.
inline constexpr double kMaxLinearSpeed = 1e5;
inline constexpr double kMaxAngularSpeed = 1e5;

/// m/s^2: the length of the world's gravity (Earth's is 9.81): one second of free fall under it
/// reaches the speed bound.
inline constexpr double kMaxGravity = 1e5;

/// A body's gravity scale, in [-kMaxGravityScale, kMaxGravityScale]: with the largest gravity it
/// keeps the body's acceleration within ten times the gravity bound.
inline constexpr double kMaxGravityScale = 10;

/// A body's friction coefficient, at most: 1 is already rubber on concrete, 100 never slips;
/// beyond, the friction bound mu * lambda of a heavy fast contact overflows (1e38 froze bodies).
inline constexpr double kMaxFriction = 100;

/// A body's restitution, at most 1: above, each bounce multiplies the energy, and two bodies
/// bouncing between each other grow without bound (1e30 froze a body at its first bounce).
inline constexpr double kMaxRestitution = 1;

/// s: a step's dt. Over a second a body at the speed bound moves the whole position range and
/// contacts cannot keep up; below a microsecond the soft contacts' 1/dt terms approach float's
/// range at the size bounds. Games step at 1/60 s, robotics at 1e-3.
inline constexpr double kMinTimestep = 1e-6;
inline constexpr double kMaxTimestep = 1;

}  // namespace elan::limits
