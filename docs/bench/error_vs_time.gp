set terminal pngcairo size 1600,1520 font 'sans,9'
set output 'docs/bench/error_vs_time.png'
set logscale xy
set format x '10^{%L}'
set format y '10^{%L}'
set grid
set key bottom left
set multiplot layout 4,4 title 'relative RMSE of pixel irradiance against wall time (trace + resolve)'
set title 'point_on_axis' noenhanced
set xlabel 'seconds'
set ylabel 'relative RMSE'
$d0_0 << EOD
0.00224998 2.45367
0.00490898 0.800998
0.0210249 0.252205
0.0871115 0.0789241
0.844957 0.0249586
8.15766 0.0080504
EOD
$d1_0 << EOD
0.000654447 2.45367
0.00154507 0.800998
0.0133282 0.252205
0.0863233 0.0789241
0.818588 0.0249586
8.02538 0.0080504
EOD
plot $d0_0 with linespoints lw 2 title 'llvmpipe (LLVM 15.0.6, 256 bits)' noenhanced, $d1_0 with linespoints lw 2 title 'CPU reference, 2 threads' noenhanced, 0.0080504*(x/8.15766)**-0.5 with lines dt 2 lc 'gray' title 'N^{-1/2}'
set title 'point_off_axis' noenhanced
set xlabel 'seconds'
set ylabel 'relative RMSE'
$d0_1 << EOD
0.0019977 3.92447
0.00248612 1.32748
0.00965927 0.424239
0.0810333 0.125531
0.982518 0.0389811
7.81879 0.0125417
EOD
$d1_1 << EOD
0.000643816 3.92447
0.00137835 1.32748
0.00939175 0.424239
0.0786179 0.125531
0.767286 0.0389811
7.43058 0.0125417
EOD
plot $d0_1 with linespoints lw 2 title 'llvmpipe (LLVM 15.0.6, 256 bits)' noenhanced, $d1_1 with linespoints lw 2 title 'CPU reference, 2 threads' noenhanced, 0.0125417*(x/7.81879)**-0.5 with lines dt 2 lc 'gray' title 'N^{-1/2}'
set title 'disk_on_axis' noenhanced
set xlabel 'seconds'
set ylabel 'relative RMSE'
$d0_2 << EOD
0.00155106 1.50901
0.00272009 0.473034
0.0132599 0.145537
0.111906 0.0485828
1.32545 0.0153916
10.782 0.00474422
EOD
$d1_2 << EOD
0.000581459 1.50901
0.00189835 0.473034
0.01368 0.145537
0.114528 0.0485828
1.11805 0.0153916
11.0947 0.00474422
EOD
plot $d0_2 with linespoints lw 2 title 'llvmpipe (LLVM 15.0.6, 256 bits)' noenhanced, $d1_2 with linespoints lw 2 title 'CPU reference, 2 threads' noenhanced, 0.00474422*(x/10.782)**-0.5 with lines dt 2 lc 'gray' title 'N^{-1/2}'
set title 'disk_off_axis' noenhanced
set xlabel 'seconds'
set ylabel 'relative RMSE'
$d0_3 << EOD
0.00120282 2.01884
0.00227561 0.618676
0.0122395 0.192406
0.104973 0.0605442
1.00806 0.0184
7.62827 0.00625028
EOD
$d1_3 << EOD
0.000458787 2.01884
0.00161271 0.618676
0.0118991 0.192406
0.104099 0.0605442
1.02622 0.0184
10.3103 0.00625028
EOD
plot $d0_3 with linespoints lw 2 title 'llvmpipe (LLVM 15.0.6, 256 bits)' noenhanced, $d1_3 with linespoints lw 2 title 'CPU reference, 2 threads' noenhanced, 0.00625028*(x/7.62827)**-0.5 with lines dt 2 lc 'gray' title 'N^{-1/2}'
set title 'furnace' noenhanced
set xlabel 'seconds'
set ylabel 'relative RMSE'
$d0_4 << EOD
0.00109529 1.95744
0.00129842 0.691132
0.0052461 0.234013
0.0468026 0.0714504
0.558591 0.0203218
4.64015 0.00700781
EOD
$d1_4 << EOD
0.000394285 1.95744
0.00136483 0.691132
0.00873828 0.234013
0.0703796 0.0714504
0.670774 0.0203218
6.69851 0.0070078
EOD
plot $d0_4 with linespoints lw 2 title 'llvmpipe (LLVM 15.0.6, 256 bits)' noenhanced, $d1_4 with linespoints lw 2 title 'CPU reference, 2 threads' noenhanced, 0.00700781*(x/4.64015)**-0.5 with lines dt 2 lc 'gray' title 'N^{-1/2}'
set title 'uniform_d65' noenhanced
set xlabel 'seconds'
set ylabel 'relative RMSE'
$d0_5 << EOD
0.000992155 0.663477
0.00279184 0.205715
0.0158301 0.0652183
0.101341 0.0189764
1.09598 0.00626652
9.74188 0.00201212
EOD
$d1_5 << EOD
0.000421066 0.663477
0.001419 0.205715
0.0120343 0.0652183
0.113828 0.0189764
1.13755 0.00626653
11.4212 0.00201212
EOD
plot $d0_5 with linespoints lw 2 title 'llvmpipe (LLVM 15.0.6, 256 bits)' noenhanced, $d1_5 with linespoints lw 2 title 'CPU reference, 2 threads' noenhanced, 0.00201212*(x/9.74188)**-0.5 with lines dt 2 lc 'gray' title 'N^{-1/2}'
set title 'uniform_a' noenhanced
set xlabel 'seconds'
set ylabel 'relative RMSE'
$d0_6 << EOD
0.000703499 0.663477
0.00169714 0.205715
0.010563 0.0652183
0.0995194 0.0189764
1.09184 0.00626653
9.70259 0.00201212
EOD
$d1_6 << EOD
0.000335703 0.663477
0.00138332 0.205715
0.011887 0.0652183
0.112234 0.0189764
1.12768 0.00626652
11.2791 0.00201212
EOD
plot $d0_6 with linespoints lw 2 title 'llvmpipe (LLVM 15.0.6, 256 bits)' noenhanced, $d1_6 with linespoints lw 2 title 'CPU reference, 2 threads' noenhanced, 0.00201212*(x/9.70259)**-0.5 with lines dt 2 lc 'gray' title 'N^{-1/2}'
set title 'uniform_f2' noenhanced
set xlabel 'seconds'
set ylabel 'relative RMSE'
$d0_7 << EOD
0.000737013 0.663477
0.0015491 0.205715
0.0110709 0.0652183
0.0938156 0.0189764
1.04014 0.00626652
9.26228 0.00201212
EOD
$d1_7 << EOD
0.00034367 0.663477
0.00118198 0.205715
0.0111579 0.0652183
0.106634 0.0189764
1.06467 0.00626653
10.5966 0.00201212
EOD
plot $d0_7 with linespoints lw 2 title 'llvmpipe (LLVM 15.0.6, 256 bits)' noenhanced, $d1_7 with linespoints lw 2 title 'CPU reference, 2 threads' noenhanced, 0.00201212*(x/9.26228)**-0.5 with lines dt 2 lc 'gray' title 'N^{-1/2}'
set title 'uniform_f11' noenhanced
set xlabel 'seconds'
set ylabel 'relative RMSE'
$d0_8 << EOD
0.000646461 0.663477
0.00156094 0.205715
0.0101667 0.0652183
0.0934506 0.0189764
1.03999 0.00626652
7.2118 0.00201212
EOD
$d1_8 << EOD
0.000357745 0.663477
0.0011814 0.205715
0.010473 0.0652183
0.104334 0.0189764
1.03699 0.00626653
10.1962 0.00201212
EOD
plot $d0_8 with linespoints lw 2 title 'llvmpipe (LLVM 15.0.6, 256 bits)' noenhanced, $d1_8 with linespoints lw 2 title 'CPU reference, 2 threads' noenhanced, 0.00201212*(x/7.2118)**-0.5 with lines dt 2 lc 'gray' title 'N^{-1/2}'
set title 'uniform_led_b3' noenhanced
set xlabel 'seconds'
set ylabel 'relative RMSE'
$d0_9 << EOD
0.000668012 0.663477
0.00136546 0.205715
0.00832493 0.0652183
0.0755552 0.0189764
0.924175 0.00626652
10.1956 0.00201212
EOD
$d1_9 << EOD
0.00040682 0.663477
0.00135457 0.205715
0.0115342 0.0652183
0.111989 0.0189764
1.11196 0.00626653
11.1012 0.00201212
EOD
plot $d0_9 with linespoints lw 2 title 'llvmpipe (LLVM 15.0.6, 256 bits)' noenhanced, $d1_9 with linespoints lw 2 title 'CPU reference, 2 threads' noenhanced, 0.00201212*(x/10.1956)**-0.5 with lines dt 2 lc 'gray' title 'N^{-1/2}'
set title 'laser_532' noenhanced
set xlabel 'seconds'
set ylabel 'relative RMSE'
$d0_10 << EOD
0.000595715 0.745339
0.00159877 0.237721
0.017198 0.0773089
0.101455 0.0238119
1.12415 0.00742963
10.2729 0.00228176
EOD
$d1_10 << EOD
0.000486659 0.745339
0.00108753 0.237721
0.0100003 0.0773089
0.098819 0.0238119
0.98981 0.00742963
9.89127 0.00228175
EOD
plot $d0_10 with linespoints lw 2 title 'llvmpipe (LLVM 15.0.6, 256 bits)' noenhanced, $d1_10 with linespoints lw 2 title 'CPU reference, 2 threads' noenhanced, 0.00228176*(x/10.2729)**-0.5 with lines dt 2 lc 'gray' title 'N^{-1/2}'
set title 'pinhole_rect' noenhanced
set xlabel 'seconds'
set ylabel 'relative RMSE'
$d0_11 << EOD
0.00139277 0.651221
0.00293005 0.191512
0.0173459 0.0673776
0.146535 0.0199254
1.50768 0.00640466
13.0324 0.00224578
EOD
$d1_11 << EOD
0.000786536 0.651221
0.00193027 0.191512
0.0161705 0.0673777
0.149833 0.0199254
1.46873 0.00640467
14.9033 0.00224578
EOD
plot $d0_11 with linespoints lw 2 title 'llvmpipe (LLVM 15.0.6, 256 bits)' noenhanced, $d1_11 with linespoints lw 2 title 'CPU reference, 2 threads' noenhanced, 0.00224578*(x/13.0324)**-0.5 with lines dt 2 lc 'gray' title 'N^{-1/2}'
set title 'pinhole_small' noenhanced
set xlabel 'seconds'
set ylabel 'relative RMSE'
$d0_12 << EOD
0.00141444 0.878509
0.0021671 0.265263
0.0127707 0.0888789
0.113066 0.0285845
1.2404 0.00867623
10.5953 0.00283295
EOD
$d1_12 << EOD
0.000489475 0.878509
0.00171192 0.265263
0.0137181 0.0888789
0.119857 0.0285845
1.27426 0.00867623
12.6485 0.00283295
EOD
plot $d0_12 with linespoints lw 2 title 'llvmpipe (LLVM 15.0.6, 256 bits)' noenhanced, $d1_12 with linespoints lw 2 title 'CPU reference, 2 threads' noenhanced, 0.00283295*(x/10.5953)**-0.5 with lines dt 2 lc 'gray' title 'N^{-1/2}'
unset multiplot
