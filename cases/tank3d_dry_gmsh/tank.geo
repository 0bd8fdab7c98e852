// The paper's fixed-roof tank (cases/tank3d_dry) drawn in Gmsh at 1.5 m
// elements: a wall of quadrilaterals in two bands (wetted below the liquid
// level, dry above), a spherical dome roof and a bottom plate of triangles,
// every normal out of the tank. Regenerate with
//   gmsh -2 -format msh41 tank.geo -o tank.msh
R = 15.0; H = 18.0; level = 14.8; Rd = 30.0; size = 1.5;
rise = Rd - Sqrt(Rd^2 - R^2);
along = Ceil(Pi * R / 2 / size);   // elements per quarter circle

Point(1) = {0, 0, 0, size};
Point(2) = {R, 0, 0, size};
Point(3) = {0, R, 0, size};
Point(4) = {-R, 0, 0, size};
Point(5) = {0, -R, 0, size};
Circle(1) = {2, 1, 3};
Circle(2) = {3, 1, 4};
Circle(3) = {4, 1, 5};
Circle(4) = {5, 1, 2};
Transfinite Curve{1, 2, 3, 4} = along + 1;

// Bottom plate: the loop runs clockwise seen from above, its normal is -z.
Curve Loop(1) = {-4, -3, -2, -1};
Plane Surface(1) = {1};

// Wall: the foot circle swept up, counter-clockwise arcs times +z = outward.
wet[] = Extrude {0, 0, level} { Curve{1, 2, 3, 4}; Layers{Ceil(level / size)}; Recombine; };
dry[] = Extrude {0, 0, H - level} { Curve{wet[0], wet[4], wet[8], wet[12]}; Layers{Ceil((H - level) / size)}; Recombine; };

// Roof: four spherical triangles from the wall-top arcs to the apex.
centre = newp; Point(centre) = {0, 0, H + rise - Rd, size};   // the dome's centre (a point of no element)
apex = newp; Point(apex) = {0, 0, H + rise, size};
rim[] = {dry[0], dry[4], dry[8], dry[12]};
For k In {0:3}
  ends[] = Boundary{ Curve{rim[k]}; };
  meridian[k] = newc; Circle(meridian[k]) = {ends[0], centre, apex};   // from the k-th arc's start to the apex
EndFor
For k In {0:3}
  loop = newll; Curve Loop(loop) = {rim[k], meridian[(k + 1) % 4], -meridian[k]};
  roof[k] = news; Surface(roof[k]) = {loop} In Sphere {centre};
EndFor

Physical Surface("wall") = {wet[1], wet[5], wet[9], wet[13], dry[1], dry[5], dry[9], dry[13]};
Physical Surface("roof") = {roof[]};
Physical Surface("bottom") = {1};
Physical Surface("wetted") = {wet[1], wet[5], wet[9], wet[13], 1};
Physical Curve("wall_top") = {rim[]};
Physical Curve("wall_foot") = {1, 2, 3, 4};
