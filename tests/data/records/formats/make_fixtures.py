# Writes the synthetic fixtures of tests/data/records/formats/ from the layouts' documentation.
# Signal: a_k = A sin(2π f k dt) except a_ks = S (the peak), in the file's units.
import math, os
OUT=os.path.dirname(os.path.abspath(__file__))
def sig(n, A, f, dt, ks, S):
    return [S if k == ks else A*math.sin(2*math.pi*f*k*dt) for k in range(n)]
def fixed(vals, per, width, dec, fmt='F'):
    lines=[]
    for i in range(0, len(vals), per):
        row=''
        for v in vals[i:i+per]:
            if fmt=='I': s=f"{int(v):{width}d}"
            elif fmt=='E': s=f"{v:{width}.{dec}e}"
            else:
                s=f"{v:{width}.{dec}f}"
                # Fortran drops the leading zero when the field is full
                if len(s)>width: s=s.replace('0.','.',1)
            assert len(s)==width,(s,width)
            row+=s
        lines.append(row)
    return lines
def w(name, lines, crlf=False):
    with open(os.path.join(OUT,name),'w',newline='') as f:
        f.write(('\r\n' if crlf else '\n').join(lines)+('\r\n' if crlf else '\n'))

# ------------------------------------------------------------- COSMOS V2, two channels + velocity
def cosmos_block(kind_line, stage, qty, units_code, chan, orient, az, n, dt, vals, peak, tpeak, data_fmt, qname, units_name, end):
    text=[f"{kind_line:<26}(Format v01.20 with 13 text lines) Src: synthetic",
          "Synthetic test record, not an earthquake   Jan 01, 2000 00:00 UTC",
          "Hypocenter: 10.0000 20.0000 H= 10km Mw=6.0",
          "Origin: 01/01/2000, 00:00:00.0 UTC",
          "Statn No: 99-00001  Code:XX-TEST  Test station, nowhere",
          "Coords: 10.1000 20.1000 Site geology: none",
          "Recorder: none s/n 1 ( 2 Chns of  2 at Sta) Sensor: none",
          "Rcrd start time:01/01/2000, 00:00:10.000 UTC (Q=5) RcrdId: synthetic",
          f"Sta Chan   {chan}: {orient} (Rcrdr Chan  {chan}) Location: ground",
          f"Raw record length = {n*dt:.3f}  sec, Uncor max =   -999 g  at   -999 sec",
          f"Processed: 01/02/2000, 12:00:00 UTC     Max = {peak:9.3f} {units_name}  at {tpeak:7.3f} sec",
          "Record filtered below 0.10  Hz (periods over  10.0 secs), and above 25.0 Hz",
          "Values used when parameter or data value is unknown/unspecified:   -999, -999.0"]
    ints=[-999]*100
    ints[0]=stage; ints[1]=qty; ints[2]=units_code; ints[3]=120; ints[49]=chan; ints[53]=az
    reals=[-999.0]*100
    reals[61]=dt*1000; reals[62]=n*dt; reals[63]=peak; reals[64]=tpeak
    out=text+[" 100 Integer-header values follow on  10 lines, Format= (10I8)"]+fixed(ints,10,8,0,'I')
    out+=[" 100 Real-header values follow on  20 lines, Format= (5F15.6)"]+fixed(reals,5,15,6)
    out+=['  2 Comment line(s) follow, each starting with a "|":',"| synthetic: a sine of 1.5 Hz and one spike","| <SCNL>TEST."+("HNZ" if az==400 else "HNE")+".XX.--"]
    per,width,dec,letter=data_fmt
    out+=[f"{n:8d} {qname} pts, approx {round(n*dt):4d} secs, units={units_name}({units_code:02d}),Format=({per}{letter}{width}.{dec})"]
    out+=fixed(vals,per,width,dec,'E' if letter=='E' else 'F')
    out+=[end]
    return out
dt=0.01; f=1.5; A=150.0
v1=sig(1000,A,f,dt,321,-456.78901)
v2=sig(997,0.4*A,f,dt,500,234.56789)
vel=[0.1*x for x in v1]
lines=cosmos_block("Corrected acceleration",2,1,4,1,"90 Deg",90,1000,dt,v1,-456.789,3.21,(8,10,5,'F'),"acceleration","cm/sec2","End-of-data for Chan 1 acceleration")
lines+=cosmos_block("Corrected velocity",2,2,5,1,"90 Deg",90,1000,dt,vel,-45.679,3.21,(8,10,5,'F'),"velocity","cm/sec","End-of-data for Chan 1 velocity")
lines+=cosmos_block("Corrected acceleration",2,1,4,2,"Up",400,997,dt,v2,234.568,5.0,(5,15,6,'E'),"acceleration","cm/sec2","End-of-data for Chan 2 acceleration")
w("cosmos_v2.v2c", lines)
# uncorrected V1, one channel, in g
g1=[x/980.665 for x in sig(600,A,f,dt,100,-456.78901)]
lines=cosmos_block("Uncorrected acceleration",1,1,2,1,"360 Deg",360,600,dt,g1,-456.78901/980.665,1.0,(8,10,6,'F'),"acceleration","g","End-of-data for Chan 1 acceleration")
w("cosmos_v1.v1c", lines)

# ------------------------------------------------------------- CSMIP/DMG V2, today's layout
def dmg_v2(chan, orient, n, dt, acc, peak, tpeak, upper=False, fmt=True):
    t=[f"Corrected accelerogram   99001-S0001-00001.01     Chan  {chan}: {orient:<8} from",
       "Uncorrected Accelerogram Data             Processed: 01/02/00, CGS  synthetic",
       "Record of Sat Jan 01, 2000 00:00:10.0 UTC             (synthetic)",
       "Synthetic test record                   (Origin:  none)",
       "99001-S0001-00001.01                 Start time:  1/01/00, 00:00:10.0 UTC",
       "Station No. 99001   10.100N, 20.100E      none  s/n 0001  (2 Chns of  2 at Sta)",
       "Test station                              CGS",
       f"Chan  {chan}: {orient}",
       "Record of Sat Jan 01, 2000 00:00:10.0 UTC    Sat Jan 01, 2000 00:00:10.0 UTC",
       "Hypocenter:  10.0N, 20.0E, H=10km        ML:  6.0",
       "Instr Period =  .0100 sec,  Damping =  .700,  Sensitivity = 1.00  v/g",
       f"                        Record length = {n*dt:6.3f} sec.",
       "                                     Uncor Max  =   .466 g , at   3.210 sec.",
       "RMS accel of (uncor) record  =        .   Chn. metadata effective date: 01/01/00",
       "Accelerogram bandpass filtered with 3 dB pts at   .10 and 25.00 cyc/sec",
       f" {n:5d} points of instrument- and baseline-corrected accel, veloc and displ data",
       f"At equally-spaced intervals of    {dt:.3f}  sec.".replace('0.','.'),
       f"Peak acceleration = {peak:9.3f}    cm/sec/sec  at {tpeak:8.3f}   sec.",
       "Peak   velocity   =    -1.000      cm/sec    at    1.000   sec.",
       "Peak displacement =     1.000        cm      at    1.000   sec.",
       "Initial velocity  =      .000   cm/sec;   Initial displacement =     .000   cm",
       "Record of Sat Jan 01, 2000 00:00:10.0 UTC    Sat Jan 01, 2000 00:00:10.0 UTC",
       "",
       f"99001-S0001-00001.01      Test station    Chan  {chan}: {orient}",
       ""]
    ints=[0]*100; ints[0]=1; ints[1]=100; ints[2]=1
    # a touching pair: 5-wide fields with 6-digit values
    ints[25]=99001; ints[26]=13043
    reals=[0.0]*100; reals[0]=0.01; reals[1]=0.7; reals[2]=n*dt
    reals[3]=-123.4567; reals[4]=-234.5678
    out=t+fixed(ints,16,5,0,'I')+fixed(reals,8,10,4)
    unit = "(UNITS: CM/SEC/SEC)" if upper else ("in cm/sec2. (8f10.5)" if fmt else "in cm/sec2.")
    head=(f" {n:5d} POINTS OF ACCEL DATA EQUALLY SPACED AT  {dt:.3f} SEC.  {unit}" if upper
          else f" {n:5d} points of accel data equally spaced at  {dt:.3f} sec, {unit}").replace(' 0.',' .')
    out+=[head]+fixed(acc,8,10,5 if not upper else 3)
    vel=[0.01*x for x in acc]; dis=[0.001*x for x in acc]
    out+=[f" {n:5d} points of veloc data equally spaced at  {dt:.3f} sec, in cm/sec.  (8f10.7)".replace(' 0.',' .')]+fixed(vel,8,10,5)
    out+=[f" {n:5d} points of displ data equally spaced at  {dt:.3f} sec, in cm.      (8f10.7)".replace(' 0.',' .')]+fixed(dis,8,10,5)
    out+=[f"/&  ----------  End of data for channel  {chan}  ----------"]
    if upper:
        out=[l.upper() for l in out]
    return out
a1=sig(1000,A,f,dt,321,-456.78901); a2=sig(997,0.4*A,f,dt,500,234.56789)
w("csmip.V2", dmg_v2(1,"360 Deg",1000,dt,a1,-456.789,3.21)+dmg_v2(2,"Up",997,dt,a2,234.568,5.0))
# 1980s upper-case layout: no format on the data line, 8F10.3
b1=sig(800,A,f,0.02,123,-456.789)
w("csmip_1980s.V2", dmg_v2(1,"90 DEG",800,0.02,b1,-456.789,2.46,upper=True), crlf=True)

# ------------------------------------------------------------- CSMIP V1, today's layout (uncorrected, g)
def dmg_v1(chan, orient, n, rate, acc_g, peak_g, tpeak):
    t=["Uncorrected Accelerogram Data             Processed: 01/02/00, CGS  synthetic",
       "Record of Sat Jan 01, 2000 00:00:10.0 UTC               (synthetic)",
       "Synthetic test record                   (Origin:  none)",
       "99001-S0001-00001.01                 Start time:  1/01/00, 00:00:10.0 UTC",
       "Station No. 99001   10.100N, 20.100E      none  s/n 0001  (1 Chns of  1 at Sta)",
       "Test station                              CGS",
       f"Chan  {chan}: {orient}",
       "Record of Sat Jan 01, 2000 00:00:10.0 UTC    Sat Jan 01, 2000 00:00:10.0 UTC",
       "Hypocenter:  10.0N, 20.0E, H=10km        ML:  6.0",
       "Instr Period =  .0100 sec,  Damping =  .700,  Sensitivity = 1.00  v/g",
       f"No. of Points = {n:6d}  Record Length = {n/rate:6.3f} sec   at {rate} Samples/sec",
       f"Units of uncor data are sec and g .        Max  = {peak_g:7.3f} g , at {tpeak:7.3f} sec.",
       "RMS calc for complete record =        .   Chn. metadata effective date: 01/01/00"]
    ints=[0]*100; ints[0]=1
    reals=[0.0]*50
    out=t+fixed(ints,16,5,0,'I')+fixed(reals,8,10,4)
    out+=[f" {n:5d} Accelerogram points at {rate} pts/sec in units of g .      Format: (8f9.6)"]
    out+=fixed(acc_g,8,9,6)
    out+=[f"/&  ----------  End of Data for Channel  {chan}  ----------"]
    return out
c=[x/980.665 for x in sig(1200,A,f,0.005,400,-456.78901)]
w("csmip.V1", dmg_v1(1,"90 Deg",1200,200,c,-0.466,2.0))

# ------------------------------------------------------------- K-NET: counts, scale 3920(gal)/6182761
scale=3920/6182761
n=3000; offset=12345
acc=sig(n,A,f,dt,777,-456.78901)
mean_a=sum(acc)/n
counts=[round(x/scale)+offset for x in acc]
kv=[(c_-sum(counts)/n)*scale for c_ in counts]
pk=max(abs(x) for x in kv)
hdr=["Origin Time       2000/01/01 00:00:00","Lat.              10.000","Long.             20.000",
     "Depth. (km)       10","Mag.              6.0","Station Code      TST001","Station Lat.      10.1000",
     "Station Long.     20.1000","Station Height(m) 10","Record Time       2000/01/01 00:00:15",
     "Sampling Freq(Hz) 100Hz",f"Duration Time(s)  {n//100}","Dir.              E-W",
     "Scale Factor      3920(gal)/6182761",f"Max. Acc. (gal)   {pk:.3f}","Last Correction   2000/01/01 00:00:00","Memo.             "]
body=[''.join(f"{c_:8d} " for c_ in counts[i:i+8]) for i in range(0,n,8)]
w("knet.EW", hdr+body)

# ------------------------------------------------------------- ESM
n=2500; esm=sig(n,A,f,0.005,900,-456.78901)
def esm_file(processing, baseline):
    h=["EVENT_NAME: SYNTHETIC","EVENT_ID: TEST-20000101_0000001","EVENT_DATE_YYYYMMDD: 20000101","EVENT_TIME_HHMMSS: 000000",
       "NETWORK: XX","STATION_CODE: TST1","STATION_NAME: Test station","DATE_TIME_FIRST_SAMPLE_YYYYMMDD_HHMMSS: 20000101_000010.000",
       "SAMPLING_INTERVAL_S: 0.005000",f"NDATA: {n}",f"DURATION_S: {n*0.005:.3f}","STREAM: HNE","UNITS: cm/s^2",
       f"PGA_CM/S^2: {456.78901:.6f}",f"TIME_PGA_S: {900*0.005:.6f}",f"BASELINE_CORRECTION: {baseline}",
       "FILTER_TYPE: BUTTERWORTH","FILTER_ORDER: 2","LOW_CUT_FREQUENCY_HZ: 0.100","HIGH_CUT_FREQUENCY_HZ: 25.000",
       "DATA_TYPE: ACCELERATION",f"PROCESSING: {processing}","USER1: synthetic","USER5: "]
    return h+[f"{x:.6f}" for x in esm]
w("esm.ASC", esm_file("manual (synthetic)","BASELINE REMOVED"))
w("esm_uncorrected.ASC", esm_file("none","BASELINE NOT REMOVED"))
print("ok")
