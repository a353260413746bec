import numpy as np
from load import *
exec(open('defl.py').read().split("run(\"IC\"")[0])
exec(open('clus.py').read().split("lab=comps(0.5)")[0].split("U=np.load")[1].split("\n",1)[1])
def compsR(th):
    lab=-np.ones(N,int);c=0;R=np.zeros((N,3))
    for s in range(N):
        if lab[s]>=0: continue
        lab[s]=c; st=[s]
        while st:
            i=st.pop()
            for j in np.nonzero(ratio[i]>th)[0]:
                if lab[j]<0: lab[j]=c; R[j]=R[i]+rel(i,j); st.append(j)
        c+=1
    return lab,R
for th in [0.4,0.3,0.2]:
    lab,R=compsR(th); sz=np.bincount(lab)
    for mn in [3,5,8]:
        for rot in [False,True]:
            Z=basis(lab,R,rot,minsize=mn)
            print(f"ratio>{th} size>={mn} rot {rot}: {Z.shape[1]} coarse dofs, largest agg {sz.max()}", end=" ")
            run("adef2",adef2(Z),Z)
