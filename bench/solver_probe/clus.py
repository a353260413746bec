import numpy as np
from load import *
exec(open('defl.py').read().split("run(\"IC\"")[0])
U=np.load('/work/runs/defl/U40.npy'); ev=np.load('/work/runs/defl/ev.npy')
tt=np.trace(Ab[:,:,:3,:3],axis1=2,axis2=3)
dg=np.diag(tt)
ratio=np.abs(tt)/np.minimum.outer(dg,dg); np.fill_diagonal(ratio,0)
# union-find clusters at 0.5
def comps(th):
    lab=-np.ones(N,int);c=0
    for s in range(N):
        if lab[s]>=0: continue
        lab[s]=c; st=[s]
        while st:
            i=st.pop()
            for j in np.nonzero(ratio[i]>th)[0]:
                if lab[j]<0: lab[j]=c; st.append(j)
        c+=1
    return lab
lab=comps(0.5); sz=np.bincount(lab)
print("clusters >=3:", (sz>=3).sum(), "sizes hist", np.bincount(sz)[:30], "largest", sz.max())
for k in range(6):
    u=U[:,k].reshape(N,6); w=(u**2).sum(1); w/=w.sum(); top=np.argsort(-w)[:6]
    print(f"mode {k} ev {ev[k]:.3f}: clusters of top bodies {lab[top]} sizes {sz[lab[top]]}")
    sub=ratio[np.ix_(top,top)]; print(np.round(sub,2))
