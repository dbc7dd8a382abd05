// Curve editing for the page: the draggable points of a curve object
// (section-case/1 JSON) and the curve rebuilt from moved points. Pure functions.
"use strict";

const Geo = (() => {
  const deg = Math.PI / 180;

  // An arc as three points: start, middle, end.
  function arcPoints(a) {
    const at = (t) => [a.center[0] + a.radius * Math.cos(t * deg), a.center[1] + a.radius * Math.sin(t * deg)];
    return [at(a.start_deg), at((a.start_deg + a.end_deg) / 2), at(a.end_deg)];
  }

  // The arc through three points (start, a point on it, end); null if they are (nearly) in line.
  function arcFrom3(p, m, q) {
    const ax = p[0], ay = p[1], bx = m[0], by = m[1], cx = q[0], cy = q[1];
    const d = 2 * (ax * (by - cy) + bx * (cy - ay) + cx * (ay - by));
    const size = Math.hypot(cx - ax, cy - ay);
    if (!(Math.abs(d) > 1e-9 * size * size)) return null;
    const a2 = ax * ax + ay * ay, b2 = bx * bx + by * by, c2 = cx * cx + cy * cy;
    const ux = (a2 * (by - cy) + b2 * (cy - ay) + c2 * (ay - by)) / d;
    const uy = (a2 * (cx - bx) + b2 * (ax - cx) + c2 * (bx - ax)) / d;
    const r = Math.hypot(ax - ux, ay - uy);
    if (!(r < 1e6 * size)) return null;
    const ang = (x, y) => Math.atan2(y - uy, x - ux) / deg;
    const mod = (v) => ((v % 360) + 360) % 360;
    const ta = ang(ax, ay), tm = mod(ang(bx, by) - ta), tb = mod(ang(cx, cy) - ta);
    const end = tm < tb ? ta + tb : ta - (360 - tb);
    return { arc: { center: [ux, uy], radius: r, start_deg: ta, end_deg: end } };
  }

  // The draggable points of a curve (a chain's joints once).
  function points(c) {
    if (c.polyline) return c.polyline.map((p) => [p[0], p[1]]);
    if (c.bspline) return c.bspline.control_points.map((p) => [p[0], p[1]]);
    if (c.arc) return arcPoints(c.arc);
    if (c.chain) {
      const out = [];
      c.chain.forEach((piece, i) => out.push(...points(piece).slice(i ? 1 : 0)));
      return out;
    }
    return [];
  }

  // The curve `c` with its draggable points replaced by P (same count); null if impossible.
  function withPoints(c, P) {
    if (c.polyline) return { polyline: P.map((p) => [p[0], p[1]]) };
    if (c.bspline) return { bspline: { ...c.bspline, control_points: P.map((p) => [p[0], p[1]]) } };
    if (c.arc) return arcFrom3(P[0], P[1], P[2]);
    if (c.chain) {
      const pieces = [];
      let k = 0;
      for (const piece of c.chain) {
        const n = points(piece).length;
        const made = withPoints(piece, P.slice(k, k + n));
        if (!made) return null;
        pieces.push(made);
        k += n - 1;
      }
      return { chain: pieces };
    }
    return null;
  }

  // Kind of each point: "end" for the curve's ends, "point" otherwise.
  function ends(c) {
    const n = points(c).length;
    return Array.from({ length: n }, (_, i) => (i === 0 || i === n - 1 ? "end" : "point"));
  }

  // The frame of a set of points: chord start A, middle M, unit chord u, unit normal n (u turned +90 deg), length L.
  function frame(P) {
    const A = P[0], B = P[P.length - 1];
    const L = Math.hypot(B[0] - A[0], B[1] - A[1]) || 1;
    const u = [(B[0] - A[0]) / L, (B[1] - A[1]) / L];
    return { A, B, M: [(A[0] + B[0]) / 2, (A[1] + B[1]) / 2], u, n: [-u[1], u[0]], L };
  }

  // The curve `c` moved by d = [dx, dy], exactly (an arc's centre moves, its radius and angles stay).
  function translated(c, d) {
    const move = (P) => P.map((p) => [p[0] + d[0], p[1] + d[1]]);
    if (c.polyline) return { ...c, polyline: move(c.polyline) };
    if (c.bspline) return { ...c, bspline: { ...c.bspline, control_points: move(c.bspline.control_points) } };
    if (c.arc) return { ...c, arc: { ...c.arc, center: [c.arc.center[0] + d[0], c.arc.center[1] + d[1]] } };
    if (c.chain) return { ...c, chain: c.chain.map((piece) => translated(piece, d)) };
    return c;
  }

  const dot = (a, b) => a[0] * b[0] + a[1] * b[1];
  const sub = (a, b) => [a[0] - b[0], a[1] - b[1]];

  // Whole-curve edits of the points P0 by a pointer moved from `from` to `to` (world units).
  function wholeEdit(kind, P0, from, to) {
    const f = frame(P0);
    const d = sub(to, from);
    if (kind === "move") return P0.map((p) => [p[0] + d[0], p[1] + d[1]]);
    if (kind === "rotate") {
      const a = Math.atan2(to[1] - f.M[1], to[0] - f.M[0]) - Math.atan2(from[1] - f.M[1], from[0] - f.M[0]);
      const c = Math.cos(a), s = Math.sin(a);
      return P0.map((p) => {
        const x = p[0] - f.M[0], y = p[1] - f.M[1];
        return [f.M[0] + c * x - s * y, f.M[1] + s * x + c * y];
      });
    }
    if (kind === "stretch") {
      const s0 = dot(sub(from, f.M), f.u);
      const k = Math.abs(s0) > 1e-12 ? Math.max(0.05, dot(sub(to, f.M), f.u) / s0) : 1;
      return P0.map((p) => {
        const r = sub(p, f.M), along = dot(r, f.u), across = dot(r, f.n);
        return [f.M[0] + k * along * f.u[0] + across * f.n[0], f.M[1] + k * along * f.u[1] + across * f.n[1]];
      });
    }
    if (kind === "bend") {
      const h = dot(d, f.n);
      return P0.map((p) => {
        const t = Math.min(1, Math.max(0, dot(sub(p, f.A), f.u) / f.L));
        const w = 4 * t * (1 - t) * h;
        return [p[0] + w * f.n[0], p[1] + w * f.n[1]];
      });
    }
    return P0;
  }

  return { arcPoints, arcFrom3, points, withPoints, ends, frame, wholeEdit, translated, dot, sub };
})();

if (typeof module !== "undefined") module.exports = Geo;
