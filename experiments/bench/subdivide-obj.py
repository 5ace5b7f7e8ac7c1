"""subdivide-obj.py SRC.obj DST.obj LEVELS: every triangle split into 4 at its edge midpoints, LEVELS
times (positions only: a large single mesh for the atlas generator's scaling; the shape is the
source's, its triangles 4^LEVELS times smaller)."""
import sys
src, dst, levels = sys.argv[1], sys.argv[2], int(sys.argv[3])
V=[]; F=[]
for line in open(src):
    if line.startswith('v '):
        V.append(tuple(map(float,line.split()[1:4])))
    elif line.startswith('f '):
        idx=[int(p.split('/')[0]) for p in line.split()[1:]]
        for i in range(1,len(idx)-1): F.append((idx[0]-1,idx[i]-1,idx[i+1]-1))
for _ in range(levels):
    mid={}
    def m(a,b):
        k=(a,b) if a<b else (b,a)
        if k not in mid:
            mid[k]=len(V); V.append(tuple((V[a][i]+V[b][i])/2 for i in range(3)))
        return mid[k]
    NF=[]
    for a,b,c in F:
        ab,bc,ca=m(a,b),m(b,c),m(c,a)
        NF+= [(a,ab,ca),(ab,b,bc),(ca,bc,c),(ab,bc,ca)]
    F=NF
with open(dst,'w') as f:
    for v in V: f.write('v %.6f %.6f %.6f\n'%v)
    for a,b,c in F: f.write('f %d %d %d\n'%(a+1,b+1,c+1))
print(len(V),len(F))
