from ic import *
order=rcm()
pat=nz|clusters(0.3,64)
print("A upper blocks", nz.sum()//2, "fill", (pat&~nz).sum()//2, flush=True)
for name,o in [("rcm",order),("natural",np.arange(N))]:
    for shift in [0.0,0.01,0.04,0.16]:
        pr=factor(o,pat,shift)
        if pr is None: print(name,shift,"breakdown",flush=True); continue
        print(name,shift,"warm",pcg(A,b,x0,pr,tol)[1],"cold",pcg(A,b,0*x0,pr,tol)[1],flush=True)
    pr=factor(o,nz,0.0)
    print(name,"IC(0) no fill:", "breakdown" if pr is None else pcg(A,b,x0,pr,tol)[1], flush=True)
