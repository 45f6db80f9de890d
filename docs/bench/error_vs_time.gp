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
0.00127574 2.45367
0.00221587 0.800998
0.00983346 0.252205
0.065933 0.0789241
0.561981 0.0249586
4.92963 0.0080504
EOD
$d1_0 << EOD
0.000419072 2.45367
0.00122147 0.800998
0.0126642 0.252205
0.125385 0.0789241
1.25036 0.0249586
12.5626 0.0080504
EOD
plot $d0_0 with linespoints lw 2 title 'llvmpipe (LLVM 15.0.6, 256 bits)' noenhanced, $d1_0 with linespoints lw 2 title 'CPU reference, 2 threads' noenhanced, 0.0080504*(x/4.92963)**-0.5 with lines dt 2 lc 'gray' title 'N^{-1/2}'
set title 'point_off_axis' noenhanced
set xlabel 'seconds'
set ylabel 'relative RMSE'
$d0_1 << EOD
0.00225306 3.92447
0.0031147 1.32748
0.011965 0.424239
0.0687881 0.125531
0.842706 0.0389811
5.16927 0.0125417
EOD
$d1_1 << EOD
0.000648806 3.92447
0.00126684 1.32748
0.0119584 0.424239
0.11665 0.125531
1.16264 0.0389811
11.6734 0.0125417
EOD
plot $d0_1 with linespoints lw 2 title 'llvmpipe (LLVM 15.0.6, 256 bits)' noenhanced, $d1_1 with linespoints lw 2 title 'CPU reference, 2 threads' noenhanced, 0.0125417*(x/5.16927)**-0.5 with lines dt 2 lc 'gray' title 'N^{-1/2}'
set title 'disk_on_axis' noenhanced
set xlabel 'seconds'
set ylabel 'relative RMSE'
$d0_2 << EOD
0.00158178 1.50901
0.00211906 0.473034
0.00869565 0.145537
0.0710408 0.0485828
0.758181 0.0153916
6.92936 0.00474422
EOD
$d1_2 << EOD
0.000529811 1.50901
0.00166819 0.473034
0.0173011 0.145537
0.16829 0.0485828
1.67969 0.0153916
16.7316 0.00474422
EOD
plot $d0_2 with linespoints lw 2 title 'llvmpipe (LLVM 15.0.6, 256 bits)' noenhanced, $d1_2 with linespoints lw 2 title 'CPU reference, 2 threads' noenhanced, 0.00474422*(x/6.92936)**-0.5 with lines dt 2 lc 'gray' title 'N^{-1/2}'
set title 'disk_off_axis' noenhanced
set xlabel 'seconds'
set ylabel 'relative RMSE'
$d0_3 << EOD
0.00137776 2.01884
0.00191329 0.618676
0.00857106 0.192406
0.0692855 0.0605442
0.73969 0.0184
6.82092 0.00625028
EOD
$d1_3 << EOD
0.000579386 2.01884
0.00150624 0.618676
0.0154184 0.192406
0.156385 0.0605442
1.55805 0.0184
15.7806 0.00625028
EOD
plot $d0_3 with linespoints lw 2 title 'llvmpipe (LLVM 15.0.6, 256 bits)' noenhanced, $d1_3 with linespoints lw 2 title 'CPU reference, 2 threads' noenhanced, 0.00625028*(x/6.82092)**-0.5 with lines dt 2 lc 'gray' title 'N^{-1/2}'
set title 'furnace' noenhanced
set xlabel 'seconds'
set ylabel 'relative RMSE'
$d0_4 << EOD
0.00114844 1.95744
0.00137181 0.691132
0.0048523 0.234013
0.0428858 0.0714504
0.506513 0.0203218
4.81417 0.00700781
EOD
$d1_4 << EOD
0.000411577 1.95744
0.00132094 0.691132
0.011949 0.234013
0.119912 0.0714504
1.19777 0.0203218
11.8962 0.0070078
EOD
plot $d0_4 with linespoints lw 2 title 'llvmpipe (LLVM 15.0.6, 256 bits)' noenhanced, $d1_4 with linespoints lw 2 title 'CPU reference, 2 threads' noenhanced, 0.00700781*(x/4.81417)**-0.5 with lines dt 2 lc 'gray' title 'N^{-1/2}'
set title 'uniform_d65' noenhanced
set xlabel 'seconds'
set ylabel 'relative RMSE'
$d0_5 << EOD
0.00132109 0.991524
0.0020226 0.285147
0.0100529 0.103361
0.0609082 0.0295802
0.667109 0.00913547
6.02591 0.00302501
EOD
$d1_5 << EOD
0.000353277 0.991524
0.00117674 0.285147
0.0124894 0.103361
0.134219 0.0295802
1.31835 0.00913547
12.8844 0.00302501
EOD
plot $d0_5 with linespoints lw 2 title 'llvmpipe (LLVM 15.0.6, 256 bits)' noenhanced, $d1_5 with linespoints lw 2 title 'CPU reference, 2 threads' noenhanced, 0.00302501*(x/6.02591)**-0.5 with lines dt 2 lc 'gray' title 'N^{-1/2}'
set title 'uniform_a' noenhanced
set xlabel 'seconds'
set ylabel 'relative RMSE'
$d0_6 << EOD
0.0011761 0.991524
0.0019911 0.285147
0.0068873 0.103361
0.0652511 0.0295802
0.663072 0.00913547
5.90636 0.00302501
EOD
$d1_6 << EOD
0.000328229 0.991524
0.0011655 0.285147
0.0120904 0.103361
0.123207 0.0295802
1.23504 0.00913547
12.685 0.00302501
EOD
plot $d0_6 with linespoints lw 2 title 'llvmpipe (LLVM 15.0.6, 256 bits)' noenhanced, $d1_6 with linespoints lw 2 title 'CPU reference, 2 threads' noenhanced, 0.00302501*(x/5.90636)**-0.5 with lines dt 2 lc 'gray' title 'N^{-1/2}'
set title 'uniform_f2' noenhanced
set xlabel 'seconds'
set ylabel 'relative RMSE'
$d0_7 << EOD
0.00106133 0.991524
0.00176155 0.285147
0.00663811 0.103361
0.0581181 0.0295802
0.640953 0.00913547
5.89608 0.00302501
EOD
$d1_7 << EOD
0.000421015 0.991524
0.000998698 0.285147
0.0112191 0.103361
0.111981 0.0295802
1.15365 0.00913547
10.5836 0.003025
EOD
plot $d0_7 with linespoints lw 2 title 'llvmpipe (LLVM 15.0.6, 256 bits)' noenhanced, $d1_7 with linespoints lw 2 title 'CPU reference, 2 threads' noenhanced, 0.00302501*(x/5.89608)**-0.5 with lines dt 2 lc 'gray' title 'N^{-1/2}'
set title 'uniform_f11' noenhanced
set xlabel 'seconds'
set ylabel 'relative RMSE'
$d0_8 << EOD
0.00136766 0.991524
0.0020652 0.285147
0.0067778 0.103361
0.0612593 0.0295802
0.658933 0.00913547
5.837 0.00302501
EOD
$d1_8 << EOD
0.000302321 0.991524
0.000983258 0.285147
0.00693166 0.103361
0.0658146 0.0295802
0.624896 0.00913547
9.41787 0.003025
EOD
plot $d0_8 with linespoints lw 2 title 'llvmpipe (LLVM 15.0.6, 256 bits)' noenhanced, $d1_8 with linespoints lw 2 title 'CPU reference, 2 threads' noenhanced, 0.00302501*(x/5.837)**-0.5 with lines dt 2 lc 'gray' title 'N^{-1/2}'
set title 'uniform_led_b3' noenhanced
set xlabel 'seconds'
set ylabel 'relative RMSE'
$d0_9 << EOD
0.00125183 0.991524
0.00186568 0.285147
0.00750285 0.103361
0.0605723 0.0295802
0.662784 0.00913547
6.00583 0.00302501
EOD
$d1_9 << EOD
0.000474627 0.991524
0.00132773 0.285147
0.0127695 0.103361
0.128628 0.0295802
1.29845 0.00913547
13.1666 0.003025
EOD
plot $d0_9 with linespoints lw 2 title 'llvmpipe (LLVM 15.0.6, 256 bits)' noenhanced, $d1_9 with linespoints lw 2 title 'CPU reference, 2 threads' noenhanced, 0.00302501*(x/6.00583)**-0.5 with lines dt 2 lc 'gray' title 'N^{-1/2}'
set title 'laser_532' noenhanced
set xlabel 'seconds'
set ylabel 'relative RMSE'
$d0_10 << EOD
0.00291362 0.745339
0.00229621 0.237721
0.00824469 0.0773089
0.0662812 0.0238119
0.695416 0.00742963
6.60082 0.00228176
EOD
$d1_10 << EOD
0.000590376 0.745339
0.00128141 0.237721
0.0146413 0.0773089
0.160421 0.0238119
1.63919 0.00742963
16.088 0.00228175
EOD
plot $d0_10 with linespoints lw 2 title 'llvmpipe (LLVM 15.0.6, 256 bits)' noenhanced, $d1_10 with linespoints lw 2 title 'CPU reference, 2 threads' noenhanced, 0.00228176*(x/6.60082)**-0.5 with lines dt 2 lc 'gray' title 'N^{-1/2}'
set title 'pinhole_rect' noenhanced
set xlabel 'seconds'
set ylabel 'relative RMSE'
$d0_11 << EOD
0.00193876 3.4756
0.00230025 1.76239
0.00537644 0.57972
0.0418974 0.173768
0.474254 0.0602742
3.87426 0.016399
EOD
$d1_11 << EOD
0.000805221 3.4756
0.00140228 1.76239
0.0114266 0.57972
0.106748 0.173768
1.06788 0.0602742
10.7041 0.016399
EOD
plot $d0_11 with linespoints lw 2 title 'llvmpipe (LLVM 15.0.6, 256 bits)' noenhanced, $d1_11 with linespoints lw 2 title 'CPU reference, 2 threads' noenhanced, 0.016399*(x/3.87426)**-0.5 with lines dt 2 lc 'gray' title 'N^{-1/2}'
unset multiplot
