// Glint against peers (docs/peers.md): POV-Ray 3.7 twin of whitted_area_dof.json.
// Render: povray +Iwhitted_area_dof.pov +Oout.exr +FE +W320 +H240 -A +WT2 -D
//         Declare=NB=16 Declare=NL=4
// NB = camera samples per pixel (blur_samples; each also jitters the pixel position, so it is
// Glint's spp), NL = area-light grid per axis (NL x NL shadow rays per hit = Glint's "samples";
// use a power of two: POV-Ray averages the grid by recursive quartering, which weighs every
// point equally only for 2, 4, 8, ...).
//
// How each Glint number maps (see docs/peers.md):
// - Right-handed like Glint: "right -x*4/3" keeps Glint's coordinates as they are.
// - Glint vfov 40 at 4:3 = POV-Ray horizontal angle 2*atan(tan(20 deg)*4/3) = 51.774009.
// - Glint lens radius a = POV-Ray aperture/4: POV-Ray offsets the eye by
//   aperture/2 * (a point of a disk of radius 1/2), so aperture = 4 * 0.12.
// - Area light: POV-Ray places grid point u at (u + jitter)/(NL-1) - 1/2 of the axis with
//   jitter in [-1/2, 1/2], so a jittered light covers NL/(NL-1) times its axes; the axes are
//   shrunk by (NL-1)/NL so that it covers Glint's 2 x 2 quad for every NL.
//   "area_illumination on" shades each point light separately, like Glint's "seed" emission
//   (POV-Ray scales that shading by the visible fraction of the grid, which it traces with
//   separately jittered points: the product of the averages where Glint averages the
//   products; the two differ near terminators). "adaptive 16" forces every grid point
//   to be traced.
// - Phong: POV-Ray "phong 0.5 phong_size 40" is ks (r.v)^p with ks = 0.5 ("specular_model":
//   "phong"); "diffuse 1" with the pigment = kd; "ambient 0.1" x ambient_light 1 = ka * I_a.
// - Glass: Fresnel reflection with conserve_energy (transmission 1 - F), ior 1.5.
// - Shadows: Glint's glass blocks light ("transparent_shadows": false, Whitted's model);
//   POV-Ray's shadow rays pass through a filtering pigment with no Fresnel loss. So the glass
//   casts no shadow here and an opaque twin of it casts the shadow: "no_image no_reflection"
//   hide the twin from camera, reflected and refracted rays; only shadow rays see it.
#version 3.7;

#ifndef (NB) #declare NB = 16; #end
#ifndef (NL) #declare NL = 4; #end
// POV-Ray's own shortcuts, off by default so that every sample is taken as in Glint:
// ADAPT = area_light "adaptive" level (16: every grid point; 0: POV-Ray's usual adaptive
// quartering, which stops where the corner samples agree), VAR = focal blur "variance"
// (0: all NB samples; POV-Ray's default 1/128 stops a pixel once its samples agree).
#ifndef (ADAPT) #declare ADAPT = 16; #end
#ifndef (VAR) #declare VAR = 0; #end

global_settings {
  assumed_gamma 1.0
  max_trace_level 11   // POV-Ray counts the camera ray as level 1; Glint's max_depth 10
  adc_bailout 1/1024   // Glint's throughput cutoff
  ambient_light rgb 1
}

background { rgb <0.55, 0.65, 0.8> }

camera {
  perspective
  location <0, 1.6, 6>
  look_at <0, 0.8, 0>
  right -x*4/3
  up y
  angle 51.774009
  aperture 0.48
  focal_point <0, 0.8, 0>
  blur_samples NB, NB
  variance VAR
  confidence 0.9
}

#declare Scale = (NL - 1) / NL;
light_source {
  <-1, 5, 2>, rgb 1
  area_light <2 * Scale, 0, 0>, <0, 0, 2 * Scale>, NL, NL
  jitter
  adaptive ADAPT
  area_illumination on
}

plane {
  y, 0
  // POV-Ray's checker cell is floor(p + 0.001), Glint's floor(p + 0.0001): the translate
  // puts the cell edges where Glint has them.
  pigment { checker rgb <0.8, 0.8, 0.8>, rgb <0.15, 0.2, 0.3> scale 1 translate <0.0009, 0, 0.0009> }
  finish { ambient 0.1 diffuse 1 specular 0 phong 0 reflection 0 }
}

sphere {
  <0.2, 0.9, 0>, 0.9
  pigment { rgbf <1, 1, 1, 1> }
  finish { ambient 0 diffuse 0 specular 0 phong 0 reflection { 0, 1 fresnel on } conserve_energy }
  interior { ior 1.5 }
  no_shadow
}

sphere {  // the glass sphere's shadow (see the header)
  <0.2, 0.9, 0>, 0.9
  pigment { rgb 0 }
  finish { ambient 0 diffuse 0 }
  no_image
  no_reflection
}

sphere {
  <-1.9, 0.8, -2>, 0.8
  pigment { rgb 0 }
  finish { ambient 0 diffuse 0 specular 0 phong 0 reflection { rgb 0.9 } }
}

sphere {
  <1.7, 0.6, 1.8>, 0.6
  pigment { rgb <0.75, 0.15, 0.1> }
  finish { ambient 0.1 diffuse 1 specular 0 phong 0.5 phong_size 40 reflection 0 }
}
