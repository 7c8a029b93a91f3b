import math, numpy as np
from smoothshaper.calibrate import synthetic as S
from smoothshaper.calibrate.modes import welch
TWO_PI=2*math.pi
fs=1000.0
tx, ax = S.resonance_record([(TWO_PI*42.0, 0.06)], fs=fs, T=8.0, snr_db=30, seed=11, axes=1, offsets=(0,))
ty, ay = S.resonance_record([(TWO_PI*33.0, 0.04), (TWO_PI*68.0, 0.07)], fs=fs, T=8.0, snr_db=30, seed=12, axes=1, offsets=(0,))
# one log: x's time stamps, y sampled at the same (jittered) instants is close enough? use x stamps for both
np.savetxt('examples/resonance_xy.csv', np.c_[tx, ax[:,0], ay[:,0]], delimiter=',', header='time,accel_x,accel_y', comments='#', fmt=['%.6f','%.2f','%.2f'])
# PSD table: a tool's output for a printer with modes at 47 Hz (x) and 31 + 58 Hz (y)
cols=[]
for modes, seed in (([(TWO_PI*47.0, 0.05)], 21), ([(TWO_PI*31.0, 0.06), (TWO_PI*58.0, 0.05)], 22)):
    t,a = S.resonance_record(modes, fs=3200.0, T=30.0, snr_db=30, seed=seed, axes=1, offsets=(0,))
    sp = welch(a[:,0], 1/3200.0)
    cols.append(sp.P)
f=sp.f; keep=(f>0)&(f<=200)
np.savetxt('examples/resonance_psd.csv', np.c_[f[keep], cols[0][keep], cols[1][keep], (cols[0]+cols[1])[keep]], delimiter=',', header='freq,psd_x,psd_y,psd_xyz', comments='', fmt='%.6g')
