"""Rotations for the independent generators (numpy, vectorised over a leading axis).

Quaternions are Hamilton, scalar first [w, x, y, z]; a quaternion q used as an
attitude maps body to world: v_W = q (0, v_B) q*.  Rotation vectors v have
Exp(v) = [cos(|v|/2), sin(|v|/2) v/|v|].  The body rate of R(t) = Exp(v(t))
is J_r(v) dv/dt with the right Jacobian J_r(v) = I - (1 - cos t)/t^2 [v]x
+ (t - sin t)/t^3 [v]x^2, t = |v| (R^T dR/dt = [J_r dv/dt]x).
"""
import math

import numpy as np


def mul(a, b):
    a = np.asarray(a, float)
    b = np.asarray(b, float)
    aw, ax, ay, az = np.moveaxis(a, -1, 0)
    bw, bx, by, bz = np.moveaxis(b, -1, 0)
    return np.stack([aw * bw - ax * bx - ay * by - az * bz,
                     aw * bx + ax * bw + ay * bz - az * by,
                     aw * by - ax * bz + ay * bw + az * bx,
                     aw * bz + ax * by - ay * bx + az * bw], axis=-1)


def conj(q):
    q = np.array(q, float)
    q[..., 1:] *= -1
    return q


def exp(v):
    v = np.asarray(v, float)
    th = np.linalg.norm(v, axis=-1)
    small = th < 1e-6
    k = np.where(small, 0.5 - th * th / 48, np.sin(th / 2) / np.where(small, 1.0, th))
    return np.concatenate([np.cos(th / 2)[..., None], v * k[..., None]], axis=-1)


def log(q):
    """Rotation vector of q (angle in [0, pi])."""
    q = np.asarray(q, float)
    q = np.where(q[..., :1] < 0, -q, q)
    n = np.linalg.norm(q[..., 1:], axis=-1)
    ang = 2 * np.arctan2(n, q[..., 0])
    small = n < 1e-12
    k = np.where(small, 2.0, ang / np.where(small, 1.0, n))
    return q[..., 1:] * k[..., None]


def rotate(q, v):
    """R(q) v."""
    q = np.asarray(q, float)
    v = np.asarray(v, float)
    u = q[..., 1:]
    t = 2 * np.cross(u, v)
    return v + q[..., :1] * t + np.cross(u, t)


def rotate_inv(q, v):
    """R(q)^T v."""
    return rotate(conj(q), v)


def angle_between(a, b):
    """The angle (rad) of the rotation from attitude a to attitude b (atan2: exact near 0)."""
    r = mul(conj(a), b)
    return 2 * math.atan2(float(np.linalg.norm(r[1:])), abs(float(r[0])))


def from_to(u, v):
    """The shortest rotation taking unit vector u onto unit vector v."""
    u = np.asarray(u, float) / np.linalg.norm(u)
    v = np.asarray(v, float) / np.linalg.norm(v)
    axis = np.cross(u, v)
    s = np.linalg.norm(axis)
    c = float(np.dot(u, v))
    if s < 1e-12:
        if c > 0:
            return np.array([1.0, 0, 0, 0])
        p = np.cross(u, [1.0, 0, 0] if abs(u[0]) < 0.9 else [0, 1.0, 0])
        return exp(p / np.linalg.norm(p) * math.pi)
    return exp(axis / s * math.atan2(s, c))


def random_unit(rng):
    while True:
        v = rng.standard_normal(3)
        n = np.linalg.norm(v)
        if n > 1e-6:
            return v / n


def right_jacobian_apply(v, vd):
    """J_r(v) vd, row by row."""
    th2 = np.sum(v * v, axis=-1)
    th = np.sqrt(th2)
    small = th < 1e-4
    ths = np.where(small, 1.0, th)
    c1 = np.where(small, 0.5 - th2 / 24, (1 - np.cos(ths)) / ths**2)
    c2 = np.where(small, 1.0 / 6 - th2 / 120, (ths - np.sin(ths)) / ths**3)
    vxvd = np.cross(v, vd)
    return vd - c1[..., None] * vxvd + c2[..., None] * np.cross(v, vxvd)
