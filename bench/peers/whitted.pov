// The built-in `whitted` scene (scenes/whitted.json) for POV-Ray 3.7, for bench/peers/raytrace_povray.py.
// POV-Ray is left-handed: every z is negated, which shows the same picture as Tessera's right-handed scene.
// Same model terms: ambient = C_r * 0.15, diffuse C_r (N.L), Phong highlight, reflection and transmission weights,
// point lights without falloff, recursion depth 6, linear output (assumed_gamma 1).
global_settings { assumed_gamma 1.0 max_trace_level 6 ambient_light rgb 1 adc_bailout 1/1000 }
background { color rgb <0.35, 0.55, 0.85> }
camera {
  perspective
  location <0, 1.6, -6.5>
  look_at <0, 0.9, 0>
  right x * 4 / 3
  angle 51.82  // horizontal field of view for fovy 40 at aspect 4:3: 2 atan(tan(20 deg) 4/3)
}
light_source { <4, 8, -6> color rgb 0.85 }
light_source { <-6, 5, -2> color rgb 0.3 }
plane {
  y, 0
  pigment { checker color rgb <0.9, 0.1, 0.1> color rgb <0.95, 0.85, 0.1> }
  finish { ambient 0.15 diffuse 1 specular 0 }
}
sphere {
  <1.0, 1.3, 1.6>, 1.3
  pigment { color rgb 0.05 }
  finish { ambient 0.15 diffuse 1 phong 0.6 phong_size 60 reflection { 0.85 } }
}
sphere {
  <-0.7, 1.0, -1.0>, 0.9
  pigment { color rgbt <1, 1, 1, 0.88> }
  finish { ambient 0 diffuse 0 phong 0.8 phong_size 120 reflection { 0.1 } }
  interior { ior 1.5 }
}
