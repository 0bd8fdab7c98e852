// Quarter of the pressurised open cylinder of ../pressurised_cylinder: R = 1 m,
// L = 2 m, 16 x 40 quadrilaterals, the generator's nodes. Regenerate with
//   gmsh -2 -format msh41 quarter_cylinder.geo -o quarter_cylinder.msh
R = 1.0; L = 2.0; around = 16; along = 40;
Point(1) = {0, 0, 0};   // the arcs' centres: geometric points of no element
Point(2) = {R, 0, 0};
Point(3) = {0, R, 0};
Point(4) = {0, 0, L};
Point(5) = {R, 0, L};
Point(6) = {0, R, L};
Circle(1) = {2, 1, 3};  // z = 0
Circle(2) = {5, 4, 6};  // z = L
Line(3) = {2, 5};       // phi = 0
Line(4) = {3, 6};       // phi = 90 degrees
// Counter-clockwise seen from outside: normals point away from the axis.
Curve Loop(1) = {1, 4, -2, -3};
Surface(1) = {1};
Transfinite Curve{1, 2} = around + 1;
Transfinite Curve{3, 4} = along + 1;
Transfinite Surface{1};
Recombine Surface{1};
Physical Surface("shell") = {1};
Physical Curve("z_start") = {1};
Physical Curve("phi_start") = {3};
Physical Curve("phi_end") = {4};
