//! Nearest hit over posed objects: order, ties, t_min, the hit record's
//! world/object points and normals, and bad transforms.

use super::{per_scalar, v3};
use crate::math::{Affine3, Mat3, Vec3};
use crate::ray::{
    InclusionTest, Intersect, Mesh, Object, ObjectError, Plane, Polygon, Ray, Sphere, nearest_hit,
};
use crate::scalar::Scalar;
use crate::transform::{Euler, Pose};

fn close<S: Scalar>(a: Vec3<S>, b: Vec3<S>, k: f64) -> bool {
    let e = k * S::EPSILON.to_f64();
    (a - b).max_abs().to_f64() <= e
}

fn nearest_over_mixed_objects<S: Scalar>() {
    let s1 = Sphere::new(Vec3::<S>::ZERO, S::ONE).unwrap();
    let floor = Plane::new(Vec3::<S>::ZERO, Vec3::Y).unwrap();
    let quad: Polygon<S, 4> = Polygon::new(&[
        v3(-1.0, -1.0, 0.0),
        v3(1.0, -1.0, 0.0),
        v3(1.0, 1.0, 0.0),
        v3(-1.0, 1.0, 0.0),
    ])
    .unwrap()
    .with_test(InclusionTest::Fan);
    let verts = [
        v3::<S>(-1.0, -1.0, 0.0),
        v3(1.0, -1.0, 0.0),
        v3(0.0, 1.0, 0.0),
    ];
    let idx = [[0u32, 1, 2]];
    let mesh = Mesh::new(&verts, &idx).unwrap();
    let at = |z: f64| Affine3::from_translation(v3::<S>(0.0, 0.0, z));
    let objects: [Object<S, &dyn Intersect<S>>; 5] = [
        Object::new(&s1 as &dyn Intersect<S>, at(10.0)).unwrap(),
        Object::new(&quad as &dyn Intersect<S>, at(6.0)).unwrap(),
        Object::new(&mesh as &dyn Intersect<S>, at(8.0)).unwrap(),
        // Floor below everything, and a duplicate of the quad (tie).
        Object::new(
            &floor as &dyn Intersect<S>,
            Affine3::from_translation(v3(0.0, -5.0, 0.0)),
        )
        .unwrap(),
        Object::new(&quad as &dyn Intersect<S>, at(6.0)).unwrap(),
    ];
    let ray = Ray::new(v3(0.0, 0.0, 0.0), v3(0.0, 0.0, 1.0)).unwrap();
    let h = nearest_hit(&ray, &objects, S::ZERO).unwrap();
    assert_eq!(
        h.id, 1,
        "the quad at z = 6; the tie with object 4 goes to the lower id"
    );
    assert!(close(h.point, v3(0.0, 0.0, 6.0), 16.0));
    assert!(close(h.object_point, Vec3::ZERO, 16.0));
    assert_eq!(h.normal.z.abs(), S::ONE);
    // Past the quads: the mesh, then the sphere.
    let h = nearest_hit(&ray, &objects, S::from_f64(7.0)).unwrap();
    assert_eq!(h.id, 2);
    assert_eq!(h.part, 0);
    let h = nearest_hit(&ray, &objects, S::from_f64(8.5)).unwrap();
    assert_eq!(h.id, 0);
    assert!(close(h.point, v3(0.0, 0.0, 9.0), 64.0));
    assert!(close(h.normal, v3(0.0, 0.0, -1.0), 64.0));
    // Downward: the floor.
    let down = Ray::new(v3(3.0, 0.0, 0.0), v3(0.0, -1.0, 0.0)).unwrap();
    let h = nearest_hit(&down, &objects, S::ZERO).unwrap();
    assert_eq!(h.id, 3);
    assert!(close(h.point, v3(3.0, -5.0, 0.0), 16.0));
    // Away from everything.
    let away = Ray::new(v3(0.0, 0.0, 0.0), v3(0.0, 1.0, -1.0)).unwrap();
    assert!(nearest_hit(&away, &objects, S::ZERO).is_none());
}

/// A scaled, rotated, translated sphere (an ellipsoid): the world normal
/// comes from the inverse transpose, and the object-space point lies on the
/// unit sphere, ready for texture coordinates.
fn transformed_object_record<S: Scalar>() {
    let sphere = Sphere::new(Vec3::<S>::ZERO, S::ONE).unwrap();
    let pose = Pose::new(
        v3::<S>(1.0, 2.0, 3.0),
        Euler::new(S::from_f64(0.3), S::from_f64(-0.2), S::from_f64(0.9)),
    );
    let scale = Mat3::from_diagonal(v3::<S>(2.0, 1.0, 0.5));
    let pw = pose.object_to_world();
    let m = Affine3::new(pw.matrix.mul_mat3(&scale), pw.translation);
    let obj = Object::new(sphere, m).unwrap();
    let target = m.transform_point3(v3(0.6, 0.0, 0.8));
    let origin = v3::<S>(9.0, -4.0, 6.0);
    let ray = Ray::through(origin, target).unwrap();
    let h = nearest_hit(&ray, core::slice::from_ref(&obj), S::ZERO).unwrap();
    let k = if S::IS_FLOAT { 256.0 } else { 2048.0 };
    assert!(close(h.point, target, k), "{:?} vs {:?}", h.point, target);
    assert!(
        close(h.object_point, v3(0.6, 0.0, 0.8), k),
        "{:?}",
        h.object_point
    );
    // Analytic normal: the inverse transpose of the linear part applied to
    // the object normal (0.6, 0, 0.8).
    let inv = m.matrix.try_inverse().unwrap();
    let n = inv.transpose().mul_vec3(v3(0.6, 0.0, 0.8)).normalize();
    assert!(close(h.normal, n, k), "{:?} vs {n:?}", h.normal);
    assert!(h.normal.dot(ray.dir()) < S::ZERO, "faces the ray");
}

fn singular_transform_is_an_error<S: Scalar>() {
    let sphere = Sphere::new(Vec3::<S>::ZERO, S::ONE).unwrap();
    let flat = Affine3::from_mat3(Mat3::from_diagonal(v3::<S>(1.0, 0.0, 1.0)));
    assert!(matches!(
        Object::new(sphere, flat).err(),
        Some(ObjectError::Singular(_))
    ));
}

per_scalar!(
    nearest_over_mixed_objects,
    transformed_object_record,
    singular_transform_is_an_error,
);
