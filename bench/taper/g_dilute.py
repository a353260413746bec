# Window means of g(r)/g_exact near the lubrication cutoff for dilute spheres (docs/lubrication-taper.md).
# usage: /usr/bin/python3 g_dilute.py RESULT.h5 [RESULT.h5 ...]
import h5py, numpy as np, sys, math
phi=0.02; n=phi/(4*math.pi/3)
def g1(r, s=2.0):
    if r>=2*s: return 1.0
    if r<s: return 0.0
    return 1.0 + n*math.pi/12*(4*s+r)*(2*s-r)**2
def load(f):
    h=h5py.File(f,'r'); return h['results/pair_distribution/r'][:], h['results/pair_distribution/g_r'][:], h['results/pair_distribution/g_r_stderr'][:]
files=sys.argv[1:]
data={f:load(f) for f in files}
r=data[files[0]][0]
print("r      exact1 " + " ".join("%-17s"%f.replace('.h5','') for f in files))
for i,ri in enumerate(r):
    if ri<2.0 or ri>2.75: continue
    if not (ri<2.12 or 2.16<ri<2.24 or 2.34<ri<2.62): continue
    row="%.3f  %.4f "%(ri,g1(ri))
    for f in files:
        g=data[f][1][i]; e=data[f][2][i]; row+=" %.3f(%+5.1f)    "%(g/g1(ri),(g-g1(ri))/e)
    print(row)
# aggregate windows
print("\nwindow averages of g/g_exact (z of the window mean)")
for lo,hi in [(2.0,2.05),(2.05,2.2),(2.2,2.5),(2.5,2.6),(2.6,3.0)]:
    row="[%.2f,%.2f) "%(lo,hi)
    for f in files:
        rr,g,e=data[f]; m=(rr>=lo)&(rr<hi)&(rr>2.0)
        ge=np.array([g1(x) for x in rr[m]]); ratio=np.sum(g[m])/np.sum(ge); err=math.sqrt(np.sum(e[m]**2))/np.sum(ge)
        row+=" %.4f+-%.4f(%+5.1f)"%(ratio,err,(ratio-1)/err)
    print(row)
