// camera.h — the two cameras of lab 1 and the switch between them.
//
//  Look-At:   the camera is given by where it is (eye), what it looks at
//             (target) and which way is up.           view = lookAt(eye, target, up)
//  Transform: the camera is an object in the world: a position and three
//             angles (yaw, pitch, roll).  C = camera → world,  view = C⁻¹
//
// Both describe the same thing — a pose — so switching modes converts the
// parameters and the view matrix does not change (see set_mode()).
//
// The math runs in double precision: a camera far from the origin (1e6) or a
// tiny scene (1e-4) keeps an orthonormal, finite view matrix.
#pragma once

#include "scene.h"

#include <glm/glm.hpp>

struct Camera {
    enum class Mode { LookAt, Transform };
    Mode mode = Mode::LookAt;

    // Look-At parameters.
    glm::dvec3 eye{0.0, 2.0, 6.0};
    glm::dvec3 target{0.0, 0.0, 0.0};
    glm::dvec3 up{0.0, 1.0, 0.0};

    // Transform parameters (degrees; positive = counter-clockwise about the axis).
    glm::dvec3 position{0.0, 2.0, 6.0};
    double yaw_deg = 0.0;    // about Y: positive turns left
    double pitch_deg = 0.0;  // about X: positive looks up
    double roll_deg = 0.0;   // about Z

    // Projection.
    double fov_y_deg = 60.0;
    double near_plane = 0.01;
    double far_plane = 100.0;

    static Camera from_scene(const lab::CameraDesc& desc);

    // The camera-to-world matrix C: camera space → world space (it places the camera; view() inverts it).
    glm::dmat4 camera_to_world() const;
    glm::dmat4 view() const { return glm::inverse(camera_to_world()); }
    // Right-handed perspective, depth in [0, 1], Y flipped for Vulkan.
    glm::dmat4 projection(double aspect) const;

    glm::dvec3 world_position() const;
    glm::dvec3 forward() const;  // unit view direction (camera −Z in world space)
    glm::dvec3 right() const;    // unit camera +X in world space

    // Switches mode keeping the pose: view() before == view() after.
    void set_mode(Mode new_mode);

    // Controls (lab 1's keyboard + mouse; see main.cpp).
    void move(const glm::dvec3& world_offset);              // translate the whole camera
    void rotate(double yaw_delta_deg, double pitch_delta_deg);  // mouse drag
    void zoom(double wheel_steps);                             // Look-At: change the distance to the target
};

// Right-handed look-at, with the fallbacks of docs/conventions.md: eye == target
// looks down −Z, and an `up` parallel to the view direction is replaced by ±Z (or ±X).
glm::dmat4 look_at_camera_to_world(const glm::dvec3& eye, const glm::dvec3& target, const glm::dvec3& up);
// C, the camera-to-world matrix, from the position and the three angles in degrees (exercise transform).
glm::dmat4 transform_camera_to_world(const glm::dvec3& position, double yaw_deg, double pitch_deg, double roll_deg);
