#!/usr/bin/env python3
"""Writes scenes/converge/veach-mis.toml (run from the repository root): four glossy plates, each
turned to face the bisector of the directions to the camera and to the middle of the light row,
so that every plate mirrors the four lights towards the camera."""
import math,sys
def norm(v):
    l=math.sqrt(sum(x*x for x in v)); return [x/l for x in v]
def add(a,b): return [x+y for x,y in zip(a,b)]
def sub(a,b): return [x-y for x,y in zip(a,b)]
def mul(a,s): return [x*s for x in a]
def cross(a,b): return [a[1]*b[2]-a[2]*b[1],a[2]*b[0]-a[0]*b[2],a[0]*b[1]-a[1]*b[0]]
C=[0,4.0,12.0]
Lc=[0,3.5,-4.0]
look=[0,0.8,0]
out=['''# A Veach-style MIS scene (after Veach & Guibas 1995, fig. 7): four glossy plates of decreasing
# sharpness (top: sharpest) each reflect four spherical lights of very different sizes but equal
# power. BSDF sampling is best for the small lights on the sharp plates, light sampling for the
# large lights on the rough ones; MIS must do well everywhere. Used by docs/sampling.md to compare
# the balance and power heuristics. Written by scripts/make-veach-mis-scene.py, which turns each
# plate to mirror the lights towards the camera.
[render]
width = 192
height = 128
spp = 64
max_depth = 2

[camera]
look_from = %s
look_at = %s
up = [0, 1, 0]
vfov = 30
''' % (C,look)]
radii=[0.03,0.1,0.3,0.9]
xs=[-3.75,-1.25,1.25,3.75]
for i,(r,x) in enumerate(zip(radii,xs)):
    rad=round(0.8/(r*r),3)
    out.append(f'''[materials.light{i}]
type = "emissive"
radiance = {rad}

[[objects]]
type = "sphere"
center = [{x}, {Lc[1]}, {Lc[2]}]
radius = {r}
material = "light{i}"
''')
exps=[5000,800,120,20]
for i,e in enumerate(exps):
    P=[0, 2.2-0.75*i, -0.2+0.9*i]
    n=norm(add(norm(sub(C,P)),norm(sub(Lc,P))))
    t=norm(cross([1,0,0],n))
    u=[9.0,0,0]; v=mul(t,0.8)
    un=cross(u,v)
    if sum(a*b for a,b in zip(un,n))<0: v=mul(v,-1)
    q=sub(sub(P,mul(u,0.5)),mul(v,0.5))
    out.append(f'''[materials.plate{i}]
type = "glossy"
albedo = 0.7
exponent = {e}

[[objects]]
type = "quad"
q = [{q[0]:.4f}, {q[1]:.4f}, {q[2]:.4f}]
u = [{u[0]:.4f}, {u[1]:.4f}, {u[2]:.4f}]
v = [{v[0]:.4f}, {v[1]:.4f}, {v[2]:.4f}]
material = "plate{i}"
''')
out.append('''[materials.floor]
type = "lambertian"
albedo = 0.2

[[objects]]
type = "quad"
q = [-20, -1.5, 20]
u = [40, 0, 0]
v = [0, 0, -40]
material = "floor"
''')
open('scenes/converge/veach-mis.toml','w').write("\n".join(out))
