#pragma once
// PLIC geometry (piecewise-linear interface calculation) in one cell, the building block of the
// conservative volume-of-fluid transport (vof/Vof.hpp).
//
// A cell is mapped onto the unit square [0, 1]^2 (X = (x - x_i)/hx, Y = (y - y_j)/hy). The
// granular part of a cut cell is the half-plane {m1 X + m2 Y <= alpha} clipped to the square:
// (m1, m2) points out of the granular phase (into the air, along grad phi, phi > 0 in the air),
// in cell units (m1 = hx n_x, m2 = hy n_y for a physical normal n). The area formulas and their
// inverse are those of Scardovelli & Zaleski (2000, J. Comput. Phys. 164:228-237, eqs. 2-3 and
// their inverse in 2D), written for any signs of m1, m2 by reflecting the square.
namespace gf::vof {

struct Line {
  double m1 = 0, m2 = 0, alpha = 0;  // granular where m1 X + m2 Y <= alpha (unit-cell coordinates)
};

// Area of {m1 X + m2 Y <= alpha} within [0, 1]^2. With m1 = m2 = 0: 1 if alpha >= 0, else 0.
double line_area(double m1, double m2, double alpha);

// The alpha for which line_area(m1, m2, alpha) = c (c clipped to [0, 1]). (m1, m2) != (0, 0).
double line_alpha(double m1, double m2, double c);

// Granular area of the line's cell inside the sub-rectangle [x0, x1] x [y0, y1] of the unit
// square, in units of the cell's area (so that a full cell gives (x1 - x0)(y1 - y0)).
double rect_area(const Line& l, double x0, double x1, double y0, double y1);

// The segment of the line inside the unit square: its two end points, (xa, ya) and (xb, yb), in
// unit-cell coordinates. false if the line does not cross the square (or touches one corner).
bool line_segment(const Line& l, double& xa, double& ya, double& xb, double& yb);

// The centroid (X, Y) of the granular part of the unit square (the polygon cut off by the
// line); returns its area. The centre (1/2, 1/2) for an empty part.
double line_centroid(const Line& l, double& X, double& Y);

// Distance from the point (px, py) to the segment (ax, ay)-(bx, by), any units.
double segment_distance(double px, double py, double ax, double ay, double bx, double by);

}  // namespace gf::vof
