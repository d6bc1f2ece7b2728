#include "vof/Plic.hpp"

#include <algorithm>
#include <cmath>

namespace gf::vof {

double line_area(double m1, double m2, double alpha) {
  // Reflect X -> 1 - X where m1 < 0 (and Y likewise): m1 X = m1 + |m1| X', so the half-plane
  // becomes |m1| X' + ... <= alpha - m1.
  if (m1 < 0) {
    alpha -= m1;
    m1 = -m1;
  }
  if (m2 < 0) {
    alpha -= m2;
    m2 = -m2;
  }
  const double s = m1 + m2;
  if (s <= 0) return alpha >= 0 ? 1.0 : 0.0;
  const double a = alpha / s;
  if (a <= 0) return 0.0;
  if (a >= 1) return 1.0;
  // Normalised m1 + m2 = 1; m <= 1/2 <= M. Three pieces: a triangle (the line cuts two
  // adjacent sides near the origin), a trapezoid, and the complement of a triangle.
  const double m = std::min(m1, m2) / s, M = std::max(m1, m2) / s;
  if (a < m) return a * a / (2 * m * M);
  if (a <= M) return (a - 0.5 * m) / M;
  const double b = 1 - a;
  return 1 - b * b / (2 * m * M);
}

double line_alpha(double m1, double m2, double c) {
  c = std::clamp(c, 0.0, 1.0);
  const double a1 = std::abs(m1), a2 = std::abs(m2), s = a1 + a2;
  if (s <= 0) return 0.0;
  const double m = std::min(a1, a2) / s, M = std::max(a1, a2) / s;
  const double c1 = 0.5 * m / M;  // the area of the corner triangle at a = m
  double a;
  if (c <= c1)
    a = std::sqrt(2 * m * M * c);
  else if (c <= 1 - c1)
    a = c * M + 0.5 * m;
  else
    a = 1 - std::sqrt(2 * m * M * (1 - c));
  // Back from the reflected square: alpha = alpha' + min(m1, 0) + min(m2, 0).
  return a * s + std::min(m1, 0.0) + std::min(m2, 0.0);
}

double rect_area(const Line& l, double x0, double x1, double y0, double y1) {
  // X = x0 + (x1 - x0) X', Y = y0 + (y1 - y0) Y': the same half-plane in the sub-rectangle's
  // own unit square.
  const double dx = x1 - x0, dy = y1 - y0;
  if (dx <= 0 || dy <= 0) return 0.0;
  return dx * dy * line_area(l.m1 * dx, l.m2 * dy, l.alpha - l.m1 * x0 - l.m2 * y0);
}

bool line_segment(const Line& l, double& xa, double& ya, double& xb, double& yb) {
  double px[4], py[4];
  int n = 0;
  const double tiny = 1e-14;
  if (std::abs(l.m2) > tiny)
    for (const double X : {0.0, 1.0}) {
      const double Y = (l.alpha - l.m1 * X) / l.m2;
      if (Y >= 0 && Y <= 1) px[n] = X, py[n++] = Y;
    }
  if (std::abs(l.m1) > tiny)
    for (const double Y : {0.0, 1.0}) {
      const double X = (l.alpha - l.m2 * Y) / l.m1;
      if (X >= 0 && X <= 1) px[n] = X, py[n++] = Y;
    }
  // The two points furthest apart (a line through a corner is found twice).
  double best = -1;
  for (int p = 0; p < n; ++p)
    for (int q = p + 1; q < n; ++q) {
      const double d = std::hypot(px[p] - px[q], py[p] - py[q]);
      if (d > best) {
        best = d;
        xa = px[p], ya = py[p], xb = px[q], yb = py[q];
      }
    }
  return best > tiny;
}

double line_centroid(const Line& l, double& X, double& Y) {
  // Clip the square (counter-clockwise) by the half-plane m1 X + m2 Y <= alpha
  // (Sutherland-Hodgman), then the centroid of the polygon by the shoelace formula.
  const double sx[4] = {0, 1, 1, 0}, sy[4] = {0, 0, 1, 1};
  double px[8], py[8];
  int n = 0;
  auto f = [&](double x, double y) { return l.m1 * x + l.m2 * y - l.alpha; };
  for (int k = 0; k < 4; ++k) {
    const double ax = sx[k], ay = sy[k], bx = sx[(k + 1) % 4], by = sy[(k + 1) % 4];
    const double fa = f(ax, ay), fb = f(bx, by);
    if (fa <= 0) px[n] = ax, py[n++] = ay;
    if ((fa < 0 && fb > 0) || (fa > 0 && fb < 0)) {
      const double t = fa / (fa - fb);
      px[n] = ax + t * (bx - ax), py[n++] = ay + t * (by - ay);
    }
  }
  double a = 0, cx = 0, cy = 0;
  for (int k = 0; k < n; ++k) {
    const int q = (k + 1) % n;
    const double cr = px[k] * py[q] - px[q] * py[k];
    a += cr;
    cx += (px[k] + px[q]) * cr;
    cy += (py[k] + py[q]) * cr;
  }
  a *= 0.5;
  if (a <= 1e-300) {
    X = Y = 0.5;
    return 0.0;
  }
  X = cx / (6 * a);
  Y = cy / (6 * a);
  return a;
}

double segment_distance(double px, double py, double ax, double ay, double bx, double by) {
  const double dx = bx - ax, dy = by - ay, len2 = dx * dx + dy * dy;
  double t = len2 > 0 ? ((px - ax) * dx + (py - ay) * dy) / len2 : 0.0;
  t = std::clamp(t, 0.0, 1.0);
  return std::hypot(px - ax - t * dx, py - ay - t * dy);
}

}  // namespace gf::vof
