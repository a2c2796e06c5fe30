#include "camera.h"

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>

namespace {
constexpr double kPi = 3.14159265358979323846;
double radians(double deg) { return deg * kPi / 180.0; }
double degrees(double rad) { return rad * 180.0 / kPi; }

// Rotation of v by `angle` radians about the unit axis k (Rodrigues' formula):
// v' = v·cosθ + (k × v)·sinθ + k·(k·v)·(1 − cosθ)
// (maybe_unused: a student copy's stubbed orbit does not call it yet.)
[[maybe_unused]] glm::dvec3 rotate_about(const glm::dvec3& v, const glm::dvec3& k, double angle) {
    const double c = std::cos(angle), s = std::sin(angle);
    return v * c + glm::cross(k, v) * s + k * glm::dot(k, v) * (1.0 - c);
}

// A unit vector, or `fallback` when v is too short to have a direction.
glm::dvec3 normalize_or(const glm::dvec3& v, const glm::dvec3& fallback) {
    const double len = glm::length(v);
    return (len > 0.0 && std::isfinite(len)) ? v / len : fallback;
}
}  // namespace

glm::dmat4 look_at_camera_to_world(const glm::dvec3& eye, const glm::dvec3& target, const glm::dvec3& up_hint) {
    // Forward f points from the eye to the target. eye == target has no
    // direction: keep the default view direction, −Z.
    const glm::dvec3 f = normalize_or(target - eye, {0.0, 0.0, -1.0});
    glm::dvec3 up = normalize_or(up_hint, {0.0, 1.0, 0.0});

    // f × up is zero when f is parallel to up (looking straight down
    // or up): then any up perpendicular to f will do. We pick ±Z so that a
    // top-down view has world −Z at the top of the image (a map's "north").
    if (glm::length(glm::cross(f, up)) < 1e-6) {
        const double side = glm::dot(f, up) > 0.0 ? 1.0 : -1.0;
        const bool f_along_z = glm::length(glm::cross(f, glm::dvec3(0.0, 0.0, 1.0))) < 1e-6;
        const glm::dvec3 axis = f_along_z ? glm::dvec3(1.0, 0.0, 0.0) : glm::dvec3(0.0, 0.0, 1.0);
        up = side * axis;
    }
    // EXERCISE look_at: which unit axes (right, true up, back) does the camera have, given f and the up hint up, and where do they and eye go in c? Read this lab's README "Look-At mode", glm::lookAt's documentation (it builds the inverse). Wrong: the target off the image centre, the scene upside down or skewed, or an empty picture. Checked by LookAt.*, Lab1Render.DefaultScene.
    // STUB: glm::dmat4 c = glm::translate(glm::dmat4(1.0), eye);  // placed at the eye, but always looking down −Z
    // Orthonormal basis: r ⟂ f and u ⟂ both; r, u, −f is right-handed.
    const glm::dvec3 r = glm::normalize(glm::cross(f, up));
    const glm::dvec3 u = glm::cross(r, f);

    // The camera-to-world matrix has the camera's axes as columns: local +X = r,
    // +Y = u, +Z = −f (the camera looks down its −Z), and the eye as origin.
    glm::dmat4 c(1.0);
    c[0] = glm::dvec4(r, 0.0);
    c[1] = glm::dvec4(u, 0.0);
    c[2] = glm::dvec4(-f, 0.0);
    c[3] = glm::dvec4(eye, 1.0);
    // END EXERCISE
    return c;
}

glm::dmat4 transform_camera_to_world(const glm::dvec3& position, double yaw_deg, double pitch_deg, double roll_deg) {
    // In which order must the turns come so that "turn left/right" always turns
    // about world up, like a person, whatever the pitch and roll?
    // EXERCISE transform: the camera-to-world matrix from position, yaw_deg, pitch_deg, roll_deg: about which axis does each angle turn, in which order, in what unit for glm::rotate? Read this lab's README "Transform mode", glm::rotate's documentation. Wrong: each angle alone looks right but together they tilt the horizon, or the view swings wildly. Checked by Transform.*, Lab1Render.TransformCameraYawPitchRoll.
    // STUB: return glm::translate(glm::dmat4(1.0), position);  // the angles are ignored
    const glm::dmat4 t = glm::translate(glm::dmat4(1.0), position);
    const glm::dmat4 ry = glm::rotate(glm::dmat4(1.0), radians(yaw_deg), glm::dvec3(0.0, 1.0, 0.0));
    const glm::dmat4 rx = glm::rotate(glm::dmat4(1.0), radians(pitch_deg), glm::dvec3(1.0, 0.0, 0.0));
    const glm::dmat4 rz = glm::rotate(glm::dmat4(1.0), radians(roll_deg), glm::dvec3(0.0, 0.0, 1.0));
    return t * ry * rx * rz;
    // END EXERCISE
}

Camera Camera::from_scene(const lab::CameraDesc& desc) {
    Camera camera;
    camera.eye = camera.position = glm::dvec3(desc.position);
    camera.target = glm::dvec3(desc.target);
    camera.up = glm::dvec3(desc.up);
    camera.yaw_deg = desc.yaw_deg;
    camera.pitch_deg = desc.pitch_deg;
    camera.roll_deg = desc.roll_deg;
    camera.fov_y_deg = desc.fov_y_deg;
    camera.near_plane = desc.near_plane;
    camera.far_plane = desc.far_plane;
    camera.mode = desc.mode == lab::CameraDesc::Mode::LookAt ? Mode::LookAt : Mode::Transform;
    return camera;
}

glm::dmat4 Camera::camera_to_world() const {
    return mode == Mode::LookAt ? look_at_camera_to_world(eye, target, up)
                                : transform_camera_to_world(position, yaw_deg, pitch_deg, roll_deg);
}

// The view matrix is the inverse of the camera-to-world matrix: it takes
// world points into camera space. (For a rigid C = T·R the inverse is
// Rᵀ·T(−p); glm::inverse computes the same in double.)

glm::dmat4 Camera::projection(double aspect) const {
    // EXERCISE projection: the camera → clip matrix from fov_y_deg, aspect, near_plane, far_plane: which GLM perspective fits a right-handed camera and Vulkan's depth range? Which way does Vulkan's clip-space Y point? Read GLM's matrix_clip_space docs, the Vulkan spec's "Coordinate Transformations". Wrong: the scene upside down, stretched, or gone. Checked by Projection.*, Lab1Render.DefaultScene.
    // STUB: glm::dmat4 p(1.0);  // no perspective at all
    glm::dmat4 p = glm::perspectiveRH_ZO(radians(fov_y_deg), aspect, near_plane, far_plane);
    p[1][1] *= -1.0;  // Vulkan's framebuffer Y points down; flip so world +Y is up on screen
    // END EXERCISE
    return p;
}

glm::dvec3 Camera::world_position() const { return glm::dvec3(camera_to_world()[3]); }
glm::dvec3 Camera::forward() const { return -glm::dvec3(camera_to_world()[2]); }
glm::dvec3 Camera::right() const { return glm::dvec3(camera_to_world()[0]); }

void Camera::set_mode(Mode new_mode) {
    if (new_mode == mode) return;
    const glm::dmat4 c = camera_to_world();
    const glm::dvec3 r(c[0]), u(c[1]), back(c[2]), p(c[3]);

    if (new_mode == Mode::Transform) {
        // Recover the angles of R, the rotation part of the Transform mode's C, from its columns:
        // multiply out its back column R·(0,0,1) in yaw and pitch first.
        position = p;
        // EXERCISE mode_switch: the yaw_deg, pitch_deg, roll_deg that rebuild this pose in the Transform order: what does back tell about pitch and yaw, what is left of r once they are undone, what range do std::asin, std::atan2 cover? Read this lab's README "Switching without a jump". Wrong: pressing C makes the view jump, flip or lose its roll, above all looking down. Checked by ModeSwitch.*.
        // STUB: yaw_deg = pitch_deg = roll_deg = 0.0;  // the view jumps
        pitch_deg = degrees(std::asin(std::clamp(-back.y, -1.0, 1.0)));
        // At pitch ±90° (gimbal lock) yaw and roll turn about the same axis, and back.x,
        // back.z are (signed) zeros or rounding noise: atan2 picks some yaw (straight down
        // from a Look-At camera gives −180°) and roll takes the rest — the pose stays exact.
        yaw_deg = degrees(std::atan2(back.x, back.z));
        // What is left after undoing yaw and pitch is Rz(roll): its first column is (cos, sin, 0).
        const glm::dmat3 undo = glm::dmat3(transform_camera_to_world({}, yaw_deg, pitch_deg, 0.0));
        const glm::dvec3 rolled = glm::transpose(undo) * r;
        roll_deg = degrees(std::atan2(rolled.y, rolled.x));
        // END EXERCISE
    } else {
        // Keep the old distance to the target (at least 1e-3, so there is a target to
        // look at; 1 if it was not finite) and use the camera's own up, so a rolled
        // camera stays rolled.
        const double distance = std::max(glm::length(target - eye), 1e-3);
        eye = p;
        target = p - back * (std::isfinite(distance) ? distance : 1.0);
        up = u;
    }
    mode = new_mode;
}

void Camera::move(const glm::dvec3& offset) {
    if (mode == Mode::LookAt) {
        eye += offset;
        target += offset;  // the whole rig moves: the view direction stays the same
    } else {
        position += offset;
    }
}

void Camera::rotate(double yaw_delta_deg, double pitch_delta_deg) {
    if (mode == Mode::Transform) {
        yaw_deg = std::remainder(yaw_deg + yaw_delta_deg, 360.0);
        pitch_deg = std::clamp(pitch_deg + pitch_delta_deg, -89.0, 89.0);  // never flip over the pole
        return;
    }
    // Look-At: the drag moves the eye over the sphere around the target; the view keeps
    // looking at the target from the same distance.
    // EXERCISE orbit: move `eye` over the sphere around `target` for a drag of yaw_delta_deg and pitch_delta_deg, with the view turning the same way as a Transform camera's (positive yaw turns left, positive pitch looks up). About which axis does each angle turn the eye, and which way? Where on the sphere must the eye stop (the tests want 1° short of that place, measured at the target), and what goes wrong if it does not? What if eye == target? Read this lab's README "Orbiting the target", rotate_about and normalize_or above. Wrong: dragging up turns the view down, the distance creeps, the picture flips over the top. Checked by Controls.Orbit*.
    // STUB: return;  // the eye stays put: dragging turns nothing
    // Yaw turns the offset eye − target about the up axis; pitch then changes its polar angle
    // (measured from up) about the axis up × offset. Positive pitch looks up, so the eye moves
    // down towards the "equator" and below. The polar angle stays within [1°, 179°]: at a pole
    // up × offset is zero (no axis to pitch about) and the view is parallel to up, where
    // look_at_camera_to_world has to guess a right axis, so the picture would spin.
    const glm::dvec3 axis = normalize_or(up, {0.0, 1.0, 0.0});
    const double radius = glm::length(eye - target);
    if (radius == 0.0) return;
    glm::dvec3 offset = rotate_about(eye - target, axis, radians(yaw_delta_deg));
    const double polar = std::acos(std::clamp(glm::dot(offset / radius, axis), -1.0, 1.0));
    const double new_polar = std::clamp(polar + radians(pitch_delta_deg), radians(1.0), radians(179.0));
    const glm::dvec3 side = glm::cross(axis, offset);
    if (glm::length(side) > 0.0) offset = rotate_about(offset, glm::normalize(side), new_polar - polar);
    eye = target + offset;
    // END EXERCISE
}

void Camera::zoom(double wheel_steps) {
    if (mode != Mode::LookAt) return;
    // Each wheel step moves 10% closer: exponential, so it feels the same at any distance.
    const glm::dvec3 offset = eye - target;
    const double distance = glm::length(offset);
    if (distance == 0.0) return;
    const double new_distance = std::clamp(distance * std::pow(0.9, wheel_steps), 1e-3, 1e6);
    eye = target + offset * (new_distance / distance);
}
