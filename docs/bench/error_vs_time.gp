set terminal pngcairo size 1600,1140 font 'sans,9'
set output 'docs/bench/error_vs_time.png'
set logscale xy
set format x '10^{%L}'
set format y '10^{%L}'
set grid
set key bottom left
set multiplot layout 3,4 title 'relative RMSE of pixel irradiance against wall time (trace + resolve)'
set title 'point_on_axis' noenhanced
set xlabel 'seconds'
set ylabel 'relative RMSE'
$d0_0 << EOD
0.00292567 2.45367
0.00345822 0.800998
0.0066534 0.252205
0.0559487 0.0789241
0.587326 0.0249586
6.54848 0.0080504
EOD
$d1_0 << EOD
0.000495025 2.45367
0.00119985 0.800998
0.0106707 0.252205
0.134507 0.0789241
1.34445 0.0249586
13.4663 0.0080504
EOD
plot $d0_0 with linespoints lw 2 title 'llvmpipe (LLVM 15.0.6, 256 bits)' noenhanced, $d1_0 with linespoints lw 2 title 'CPU reference, 2 threads' noenhanced, 0.0080504*(x/6.54848)**-0.5 with lines dt 2 lc 'gray' title 'N^{-1/2}'
set title 'point_off_axis' noenhanced
set xlabel 'seconds'
set ylabel 'relative RMSE'
$d0_1 << EOD
0.00278185 3.92447
0.00608896 1.32748
0.0167742 0.424239
0.073457 0.125531
0.807131 0.0389811
6.73702 0.0125417
EOD
$d1_1 << EOD
0.000550681 3.92447
0.0013052 1.32748
0.0123698 0.424239
0.125235 0.125531
1.25254 0.0389811
12.4235 0.0125417
EOD
plot $d0_1 with linespoints lw 2 title 'llvmpipe (LLVM 15.0.6, 256 bits)' noenhanced, $d1_1 with linespoints lw 2 title 'CPU reference, 2 threads' noenhanced, 0.0125417*(x/6.73702)**-0.5 with lines dt 2 lc 'gray' title 'N^{-1/2}'
set title 'disk_on_axis' noenhanced
set xlabel 'seconds'
set ylabel 'relative RMSE'
$d0_2 << EOD
0.0029806 1.50901
0.00337466 0.473034
0.011741 0.145537
0.0903915 0.0485828
0.907526 0.0153916
8.88003 0.00474422
EOD
$d1_2 << EOD
0.000477933 1.50901
0.00156783 0.473034
0.017187 0.145537
0.176018 0.0485828
1.74105 0.0153916
17.7724 0.00474422
EOD
plot $d0_2 with linespoints lw 2 title 'llvmpipe (LLVM 15.0.6, 256 bits)' noenhanced, $d1_2 with linespoints lw 2 title 'CPU reference, 2 threads' noenhanced, 0.00474422*(x/8.88003)**-0.5 with lines dt 2 lc 'gray' title 'N^{-1/2}'
set title 'disk_off_axis' noenhanced
set xlabel 'seconds'
set ylabel 'relative RMSE'
$d0_3 << EOD
0.00143758 2.01884
0.00388597 0.618676
0.0105901 0.192406
0.0886666 0.0605442
0.878099 0.0184
6.37516 0.00625028
EOD
$d1_3 << EOD
0.000525683 2.01884
0.00188924 0.618676
0.017196 0.192406
0.168577 0.0605442
1.69915 0.0184
17.3 0.00625028
EOD
plot $d0_3 with linespoints lw 2 title 'llvmpipe (LLVM 15.0.6, 256 bits)' noenhanced, $d1_3 with linespoints lw 2 title 'CPU reference, 2 threads' noenhanced, 0.00625028*(x/6.37516)**-0.5 with lines dt 2 lc 'gray' title 'N^{-1/2}'
set title 'furnace' noenhanced
set xlabel 'seconds'
set ylabel 'relative RMSE'
$d0_4 << EOD
0.000705012 1.95744
0.0011548 0.691132
0.00432976 0.234013
0.0381416 0.0714504
0.453256 0.0203218
3.81223 0.00700781
EOD
$d1_4 << EOD
0.000382594 1.95744
0.00130255 0.691132
0.0129477 0.234013
0.128311 0.0714504
1.29796 0.0203218
12.2973 0.0070078
EOD
plot $d0_4 with linespoints lw 2 title 'llvmpipe (LLVM 15.0.6, 256 bits)' noenhanced, $d1_4 with linespoints lw 2 title 'CPU reference, 2 threads' noenhanced, 0.00700781*(x/3.81223)**-0.5 with lines dt 2 lc 'gray' title 'N^{-1/2}'
set title 'uniform_d65' noenhanced
set xlabel 'seconds'
set ylabel 'relative RMSE'
$d0_5 << EOD
0.00139493 0.991524
0.00140247 0.285147
0.00872567 0.103361
0.0588346 0.0295802
0.588881 0.00913547
5.42904 0.00302501
EOD
$d1_5 << EOD
0.000359579 0.991524
0.00113296 0.285147
0.0126899 0.103361
0.135446 0.0295802
1.34222 0.00913547
13.8847 0.00302501
EOD
plot $d0_5 with linespoints lw 2 title 'llvmpipe (LLVM 15.0.6, 256 bits)' noenhanced, $d1_5 with linespoints lw 2 title 'CPU reference, 2 threads' noenhanced, 0.00302501*(x/5.42904)**-0.5 with lines dt 2 lc 'gray' title 'N^{-1/2}'
set title 'uniform_a' noenhanced
set xlabel 'seconds'
set ylabel 'relative RMSE'
$d0_6 << EOD
0.000856077 0.991524
0.00126811 0.285147
0.00602202 0.103361
0.0546385 0.0295802
0.59318 0.00913547
5.44364 0.00302501
EOD
$d1_6 << EOD
0.000425184 0.991524
0.00120156 0.285147
0.0129382 0.103361
0.137831 0.0295802
1.37993 0.00913547
13.7801 0.00302501
EOD
plot $d0_6 with linespoints lw 2 title 'llvmpipe (LLVM 15.0.6, 256 bits)' noenhanced, $d1_6 with linespoints lw 2 title 'CPU reference, 2 threads' noenhanced, 0.00302501*(x/5.44364)**-0.5 with lines dt 2 lc 'gray' title 'N^{-1/2}'
set title 'uniform_f2' noenhanced
set xlabel 'seconds'
set ylabel 'relative RMSE'
$d0_7 << EOD
0.00134833 0.991524
0.00208639 0.285147
0.00760526 0.103361
0.0591779 0.0295802
0.571346 0.00913547
5.05459 0.00302501
EOD
$d1_7 << EOD
0.000315096 0.991524
0.00104386 0.285147
0.0115814 0.103361
0.124548 0.0295802
1.23618 0.00913547
12.4572 0.003025
EOD
plot $d0_7 with linespoints lw 2 title 'llvmpipe (LLVM 15.0.6, 256 bits)' noenhanced, $d1_7 with linespoints lw 2 title 'CPU reference, 2 threads' noenhanced, 0.00302501*(x/5.05459)**-0.5 with lines dt 2 lc 'gray' title 'N^{-1/2}'
set title 'uniform_f11' noenhanced
set xlabel 'seconds'
set ylabel 'relative RMSE'
$d0_8 << EOD
0.00103915 0.991524
0.00119249 0.285147
0.0081685 0.103361
0.0544271 0.0295802
0.587057 0.00913547
5.08897 0.00302501
EOD
$d1_8 << EOD
0.000347548 0.991524
0.000969492 0.285147
0.0111616 0.103361
0.12011 0.0295802
1.22433 0.00913547
12.0916 0.003025
EOD
plot $d0_8 with linespoints lw 2 title 'llvmpipe (LLVM 15.0.6, 256 bits)' noenhanced, $d1_8 with linespoints lw 2 title 'CPU reference, 2 threads' noenhanced, 0.00302501*(x/5.08897)**-0.5 with lines dt 2 lc 'gray' title 'N^{-1/2}'
set title 'uniform_led_b3' noenhanced
set xlabel 'seconds'
set ylabel 'relative RMSE'
$d0_9 << EOD
0.00142164 0.991524
0.00251938 0.285147
0.00677325 0.103361
0.0526629 0.0295802
0.571673 0.00913547
5.15866 0.00302501
EOD
$d1_9 << EOD
0.000311349 0.991524
0.00112275 0.285147
0.01293 0.103361
0.135929 0.0295802
1.34113 0.00913547
8.34472 0.003025
EOD
plot $d0_9 with linespoints lw 2 title 'llvmpipe (LLVM 15.0.6, 256 bits)' noenhanced, $d1_9 with linespoints lw 2 title 'CPU reference, 2 threads' noenhanced, 0.00302501*(x/5.15866)**-0.5 with lines dt 2 lc 'gray' title 'N^{-1/2}'
set title 'laser_532' noenhanced
set xlabel 'seconds'
set ylabel 'relative RMSE'
$d0_10 << EOD
0.000450351 0.745339
0.000933143 0.237721
0.00540838 0.0773089
0.0602428 0.0238119
0.642025 0.00742963
6.24808 0.00228176
EOD
$d1_10 << EOD
0.000454228 0.745339
0.00104188 0.237721
0.00790992 0.0773089
0.0753757 0.0238119
0.755689 0.00742963
7.53895 0.00228175
EOD
plot $d0_10 with linespoints lw 2 title 'llvmpipe (LLVM 15.0.6, 256 bits)' noenhanced, $d1_10 with linespoints lw 2 title 'CPU reference, 2 threads' noenhanced, 0.00228176*(x/6.24808)**-0.5 with lines dt 2 lc 'gray' title 'N^{-1/2}'
set title 'pinhole_rect' noenhanced
set xlabel 'seconds'
set ylabel 'relative RMSE'
$d0_11 << EOD
0.00186925 3.4756
0.00202408 1.76239
0.00505289 0.57972
0.0358052 0.173768
0.430811 0.0602742
3.46488 0.016399
EOD
$d1_11 << EOD
0.000521325 3.4756
0.00115164 1.76239
0.00667185 0.57972
0.056155 0.173768
0.554624 0.0602742
5.56415 0.016399
EOD
plot $d0_11 with linespoints lw 2 title 'llvmpipe (LLVM 15.0.6, 256 bits)' noenhanced, $d1_11 with linespoints lw 2 title 'CPU reference, 2 threads' noenhanced, 0.016399*(x/3.46488)**-0.5 with lines dt 2 lc 'gray' title 'N^{-1/2}'
unset multiplot
