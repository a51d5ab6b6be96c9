#!/usr/bin/env python3
"""Writes yard-KIND.gltf (KIND: point, spot or directional): a floor and 144
boxes of varied height under one KHR_lights_punctual key light, to time the
shadow pass of each light type (a point light renders six cube faces)."""
import json, struct, base64, sys, math
kind = sys.argv[1]
# A unit cube: 6 faces x 4 vertices with face normals.
pos=[];nrm=[];idx=[]
faces=[((1,0,0),(0,1,0),(0,0,1)),((-1,0,0),(0,1,0),(0,0,-1)),((0,1,0),(0,0,1),(1,0,0)),
       ((0,-1,0),(0,0,-1),(1,0,0)),((0,0,1),(1,0,0),(0,1,0)),((0,0,-1),(-1,0,0),(0,1,0))]
for n,u,v in faces:
    base=len(pos)
    for su,sv in ((-1,-1),(1,-1),(1,1),(-1,1)):
        pos.append(tuple(0.5*(n[i]+su*u[i]+sv*v[i]) for i in range(3))); nrm.append(n)
    idx += [base,base+1,base+2,base,base+2,base+3]
buf=b''.join(struct.pack('<3f',*p) for p in pos)+b''.join(struct.pack('<3f',*p) for p in nrm)+b''.join(struct.pack('<H',i) for i in idx)
nodes=[{"mesh":0,"scale":[20,0.2,20],"translation":[0,-0.1,0]}]
for i in range(12):
    for j in range(12):
        nodes.append({"mesh":0,"translation":[-8.25+1.5*i,0.5,-8.25+1.5*j],"scale":[0.6,1+((i*7+j*3)%5)*0.4,0.6]})
light={"point":{"type":"point","intensity":20000},
       "spot":{"type":"spot","intensity":20000,"spot":{"innerConeAngle":1.0,"outerConeAngle":1.3}},
       "directional":{"type":"directional","intensity":2000}}[kind]
s=math.sqrt(0.5)
nodes.append({"translation":[0.3,4,0.2],"rotation":[-s,0,0,s],"extensions":{"KHR_lights_punctual":{"light":0}}})
nodes.append({"camera":0,"translation":[0,9,14],"rotation":[-0.2588,0,0,0.9659]})
g={"asset":{"version":"2.0"},"buffers":[{"byteLength":len(buf),"uri":"data:application/octet-stream;base64,"+base64.b64encode(buf).decode()}],
 "bufferViews":[{"buffer":0,"byteOffset":0,"byteLength":288},{"buffer":0,"byteOffset":288,"byteLength":288},{"buffer":0,"byteOffset":576,"byteLength":72}],
 "accessors":[{"bufferView":0,"componentType":5126,"type":"VEC3","count":24,"min":[-0.5]*3,"max":[0.5]*3},{"bufferView":1,"componentType":5126,"type":"VEC3","count":24},{"bufferView":2,"componentType":5123,"type":"SCALAR","count":36}],
 "meshes":[{"primitives":[{"attributes":{"POSITION":0,"NORMAL":1},"indices":2}]}],
 "cameras":[{"type":"perspective","perspective":{"yfov":0.9,"znear":0.1}}],
 "nodes":nodes,"scenes":[{"nodes":list(range(len(nodes)))}],"scene":0,
 "extensionsUsed":["KHR_lights_punctual"],"extensions":{"KHR_lights_punctual":{"lights":[light]}}}
open(f"yard-{kind}.gltf","w").write(json.dumps(g))
