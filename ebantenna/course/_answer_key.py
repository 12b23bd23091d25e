"""Sealed answers of the exercises and their tolerances: ebantenna.course's key.

Written by ``docs/_tools/make_answer_key.py`` from the worked solutions in
``docs/exercises/solutions/``; do not edit by hand. Each answer is held as the stretched, salted
hashes of the cells within its tolerance (see :func:`ebantenna.course.seal`), not as a value.
The test suite checks that it seals what the solutions compute.
"""

ANSWER_KEY = {
    'ex01_element': {
        'M11': {
            'kind': 'abs', 'width': 1e-06,
            'salt': 'ex01_element/M11',
            'kdf': {'name': 'scrypt', 'n': 2048, 'r': 8, 'p': 1},
            'cells': [
                '0e74455132716db8', '3df26a7a18c8f9a2', '6df8778cdcb9040c', '7d152c4a110363f5',
                '8ce7846ca41ede92', 'a7640fadc6403d1d', 'c0203fe3ad5b093f', 'e0ba8224c0069976',
                'e44eb8503ecdc41f', 'f9b11d49e12badd4', 'ff5927b232b33d4a',
            ],
            'reason': (
                'exact rational arithmetic gives an integer; 1e-6 admits a floating-point '
                'quadrature'
            ),
        },
        'M14': {
            'kind': 'abs', 'width': 1e-06,
            'salt': 'ex01_element/M14',
            'kdf': {'name': 'scrypt', 'n': 2048, 'r': 8, 'p': 1},
            'cells': [
                '463b81fdf674f995', '484de53be72bccbf', '4b99482a10ce62cb', '56ec309e512b22d7',
                '5bb33e2a6500ccd8', '5e9efa93a9baf093', '6ee883e88dfff924', '7e811e3b788e7fa3',
                '8e447d16e025992e', 'a30c0ba6dde35caf', 'e68fae6f97eaef15',
            ],
            'reason': (
                'exact rational arithmetic gives an integer; 1e-6 admits a floating-point '
                'quadrature'
            ),
        },
    },
    'ex02_assembly': {
        'n_typos_K1': {
            'kind': 'abs', 'width': 0.0,
            'salt': 'ex02_assembly/n_typos_K1',
            'kdf': {'name': 'scrypt', 'n': 2048, 'r': 8, 'p': 1},
            'cells': [
                '33f4163c33759824',
            ],
            'reason': (
                'a count of matrix entries'
            ),
        },
        'K33': {
            'kind': 'rel', 'width': 1e-09,
            'salt': 'ex02_assembly/K33',
            'kdf': {'name': 'scrypt', 'n': 2048, 'r': 8, 'p': 1},
            'cells': [
                '167a2daf074db2b1', '2938f2367a843ee9', '824addc448fe346b', '85a15705b0b2c8d7',
                'cbb0199a4ce6e0dc', 'cf3bea4c77bb94f0', 'd2d9f5dadf1c4d30', 'd79348403e7cf4df',
                'd8208d1ba0f691b3', 'da779f4ee9496686', 'f48fbc039e0bd99f',
            ],
            'reason': (
                'the same two terms added in any order: only the last of 16 digits can differ'
            ),
        },
        'M33': {
            'kind': 'rel', 'width': 1e-09,
            'salt': 'ex02_assembly/M33',
            'kdf': {'name': 'scrypt', 'n': 2048, 'r': 8, 'p': 1},
            'cells': [
                '1a31bc1f0f4da592', '214829abe118df06', '3f67a642fe576791', '5118f55ca62ff17a',
                '5a104c804e3c5ad6', '758d94160090eb29', '86814e04986d276a', 'a1b1eeb0f2569056',
                'be04581982b567c3', 'c705c2c029ee88e5', 'e6d0d7983a4cdc28',
            ],
            'reason': (
                'the same two terms added in any order: only the last of 16 digits can differ'
            ),
        },
    },
    'ex03_convergence': {
        'order_mode1': {
            'kind': 'abs', 'width': 0.01,
            'salt': 'ex03_convergence/order_mode1',
            'kdf': {'name': 'scrypt', 'n': 2048, 'r': 8, 'p': 1},
            'cells': [
                '15ad9b70e1de3675', '3a5cfb3564bde326', '55a8289222d22e96', '701f3473f73000f1',
                '9a42380f105cbac3', '9ea1015d4a913949', 'b698711312f70e89', 'c546bab9214571e9',
                'cc5e04a165cd1337', 'df6aee736657a6d8', 'f4a04e54d3a62b7e',
            ],
            'reason': (
                'the same meshes give the same order to many digits; 0.01 admits an own exact '
                'solver'
            ),
        },
        'order_mode2': {
            'kind': 'abs', 'width': 0.01,
            'salt': 'ex03_convergence/order_mode2',
            'kdf': {'name': 'scrypt', 'n': 2048, 'r': 8, 'p': 1},
            'cells': [
                '0ca4b91edb7b9002', '1f9cfb34a4d760d9', '2355340f78fe2efa', '235b7fd01ea78135',
                '3a03882cd1bb5cbf', '4513ddd8267668eb', '4fbbc1163f9b273c', '95b05ba932d72a5e',
                'bad857b18c6f2d49', 'ebcb5c5fbd3faf50', 'efe4449ac5513825',
            ],
            'reason': (
                'the same meshes give the same order to many digits; 0.01 admits an own exact '
                'solver'
            ),
        },
        'error64_mode1': {
            'kind': 'rel', 'width': 0.01,
            'salt': 'ex03_convergence/error64_mode1',
            'kdf': {'name': 'scrypt', 'n': 2048, 'r': 8, 'p': 1},
            'cells': [
                '08fd95c63a43eba2', '3bc4bc4ac9ce226b', '3d501ea7949a3863', '5a2d487ff6d45ad6',
                '621ead9e8c7cfc30', '78cf0c9f0c7c02dc', 'af81815b91626328', 'b4f5636029d7eb0e',
                'dfb92dc053e0cb1a', 'f87492fd45da2fc9', 'f87e8c477d424f98',
            ],
            'reason': (
                'an exact frequency from an own root-finder (tolerance 1e-12 or finer) moves this'
                ' nine-digit difference by up to about 1 %'
            ),
        },
    },
    'ex04_peak': {
        'a_peak_cm': {
            'kind': 'abs', 'width': 0.05,
            'salt': 'ex04_peak/a_peak_cm',
            'kdf': {'name': 'scrypt', 'n': 2048, 'r': 8, 'p': 1},
            'cells': [
                '06dfacfc182e2833', '0d67e466453379ad', '3a4969bcfb64b987', '493034a93c548347',
                '4a8be2c721b7ca2b', '5683123e9f7391ed', '840670e428e100e9', 'a286241ba08df24b',
                'c16f786f26d8f44c', 'd505d11c2e3de205', 'eb60f4917969b699',
            ],
            'reason': (
                'the maximum is flat: a search on a 1e-3 L grid or a bounded optimiser find it '
                'within 1e-3 L (0.045 cm at most)'
            ),
        },
        'f_peak': {
            'kind': 'rel', 'width': 0.0001,
            'salt': 'ex04_peak/f_peak',
            'kdf': {'name': 'scrypt', 'n': 2048, 'r': 8, 'p': 1},
            'cells': [
                '05dc6683b29efd59', '3e5be787ed026a4c', '624a0d154d8212c2', '7790cd0204f975e7',
                '832d9a223981b03b', '8896312931d4b76e', '97918f7b3d9cb7f2', 'a5a0fe88ea71364b',
                'bd388248c0200f95', 'd2b8acc2c98ca5e1', 'dc79dd42c7d89886',
            ],
            'reason': (
                'at a flat maximum an error of 1e-3 L in the place changes the frequency by far '
                'less than 1e-4'
            ),
        },
        'a_peak_two_elements_cm': {
            'kind': 'abs', 'width': 0.05,
            'salt': 'ex04_peak/a_peak_two_elements_cm',
            'kdf': {'name': 'scrypt', 'n': 2048, 'r': 8, 'p': 1},
            'cells': [
                '00727aec4ffa7b13', '2bf5c6f7c7b2c865', '2e6513495c4b3a24', '4bc2077b4f1367d6',
                '4f85a06996b0519e', '769f71eaa0b95a60', '77f7c867e92dbd7e', '788f44333d64c0e7',
                'a9215d76e620135f', 'eb8d5b98fbd49726', 'f4df74382afa64eb',
            ],
            'reason': (
                'the maximum is flat: a search on a 1e-3 L grid or a bounded optimiser find it '
                'within 1e-3 L (0.045 cm at most)'
            ),
        },
        'a_twin_cm': {
            'kind': 'abs', 'width': 0.05,
            'salt': 'ex04_peak/a_twin_cm',
            'kdf': {'name': 'scrypt', 'n': 2048, 'r': 8, 'p': 1},
            'cells': [
                '10cec34aaab9cda0', '3ad8b9a6373d5927', '463cd5a3db0df224', '4cb405e2d664a422',
                '762f4d36a2376964', '77e2992f56c3cee7', '8b594c3a421ac3e3', 'a2c25f44c4bc9249',
                'b1f1f6f06c906c41', 'e891134fe40d7d59', 'f02e6cd04c521d4c',
            ],
            'reason': (
                'any root-finder (or a 1e-3 L grid) on f(a) - f(twin_of L) beyond the maximum'
            ),
        },
    },
    'ex05_decay': {
        'tau_hand_ms': {
            'kind': 'rel', 'width': 0.04,
            'salt': 'ex05_decay/tau_hand_ms',
            'kdf': {'name': 'scrypt', 'n': 2048, 'r': 8, 'p': 1},
            'cells': [
                '2685da728aa48b24', '431110729715d63a', '54e16994a161a8b4', '6070d83a3bd3b7ae',
                '6903772cd748621f', 'a1d0783e4e4fe7f2', 'b5289843fa8c0247', 'c26808f660b49ba7',
                'e2643b88a6559448', 'e52724ff83d101dc', 'fd3c76cee470d41f',
            ],
            'reason': (
                'the window (ending 10 to 30 ms in, while the envelope is well above the noise) '
                'moves it by up to 4 %'
            ),
        },
        'tau_fit_ms': {
            'kind': 'rel', 'width': 0.002,
            'salt': 'ex05_decay/tau_fit_ms',
            'kdf': {'name': 'scrypt', 'n': 2048, 'r': 8, 'p': 1},
            'cells': [
                '0d03efba2e4f2f50', '0dbbf22f5942e4ad', '29b59d8346ff9e78', '2ad94728641b5c62',
                '48575189b9f9c639', '49255a82ab0ef925', '74b1d9f608ba2e25', 'bbda1cd41665f669',
                'beca2b660772a6de', 'f1fade1ed1d8819c', 'ff561b048124ba79',
            ],
            'reason': (
                'fit_decay on these samples; a record cut to 500 to 800 samples moves it by up to'
                ' 0.2 %'
            ),
        },
        'a_fit': {
            'kind': 'rel', 'width': 0.002,
            'salt': 'ex05_decay/a_fit',
            'kdf': {'name': 'scrypt', 'n': 2048, 'r': 8, 'p': 1},
            'cells': [
                '0b725d110579d3d9', '22e259aa827c005a', '2e39acc665a463a3', '5205ccef6e9431e4',
                '8b20d8545eb76ce1', '99b4a72cc5bcde5d', 'a5bd6fade4b464e3', 'c3b0c31f55b69bc9',
                'd7fc14680b88fe55', 'fa4fc7a35638ffbd', 'faae21a47e89a53f',
            ],
            'reason': (
                'fit_decay on these samples; a record cut to 500 to 800 samples moves it by up to'
                ' 0.2 %'
            ),
        },
    },
    'ex06_svm_dual': {
        'w1': {
            'kind': 'abs', 'width': 0.001,
            'salt': 'ex06_svm_dual/w1',
            'kdf': {'name': 'scrypt', 'n': 2048, 'r': 8, 'p': 1},
            'cells': [
                '09fb4a1640de2f6c', '0cce657bed6b3109', '253e050e91374bd3', '288cbaa8eb022588',
                '2acd17cce48fffdf', '90c6da3c8fd19e73', '993ef3706f078a60', 'a71040a71f41454c',
                'c93174d7e324835f', 'cedb0ad0eb2bf7fc', 'dcf50cff69b73c08',
            ],
            'reason': (
                'solvers stop at their own tolerance: SLSQP and SMO here agree to 1e-4'
            ),
        },
        'w2': {
            'kind': 'abs', 'width': 0.001,
            'salt': 'ex06_svm_dual/w2',
            'kdf': {'name': 'scrypt', 'n': 2048, 'r': 8, 'p': 1},
            'cells': [
                '0edf9ceb7be8224d', '1bf437506ad9a435', '3c0530e01b1582db', '5d73102ada549b71',
                '74e307584c9b4bf8', '7a686520fd2e3706', '9a9da764bcfe17d2', 'aa93800aafd56e25',
                'c23b3809b5154ac9', 'd35e027f29aebfad', 'f68804d13bcc2c79',
            ],
            'reason': (
                'solvers stop at their own tolerance: SLSQP and SMO here agree to 1e-4'
            ),
        },
        'b': {
            'kind': 'abs', 'width': 0.001,
            'salt': 'ex06_svm_dual/b',
            'kdf': {'name': 'scrypt', 'n': 2048, 'r': 8, 'p': 1},
            'cells': [
                '0cc97e3b164db631', '1c689e7ebc6e0637', '2d52fe7469f8625a', '3df2dcd98243ebec',
                'ad505943298a9572', 'cc3323984217fcba', 'db0fc8552e29e8bc', 'e79829068a446c1d',
                'e87ed7a5ef33ce38', 'ed9f720c13f73e72', 'ffb5989d07c7102a',
            ],
            'reason': (
                'solvers stop at their own tolerance: SLSQP and SMO here agree to 1e-4'
            ),
        },
        'n_support': {
            'kind': 'abs', 'width': 0.0,
            'salt': 'ex06_svm_dual/n_support',
            'kdf': {'name': 'scrypt', 'n': 2048, 'r': 8, 'p': 1},
            'cells': [
                '8d092f70fa2f4527',
            ],
            'reason': (
                'a count: multipliers above 1e-6'
            ),
        },
        'dual_objective': {
            'kind': 'abs', 'width': 0.0001,
            'salt': 'ex06_svm_dual/dual_objective',
            'kdf': {'name': 'scrypt', 'n': 2048, 'r': 8, 'p': 1},
            'cells': [
                '015ec6f99298c1aa', '039ac27b336a27d9', '0fc54a15065f2d1d', '6be104886ec0d505',
                '6dd0b5c373712d94', 'b31cac4dbd943a0a', 'c0e47437a6a8aadf', 'c3bfb79806f53b30',
                'c4a302862b106411', 'c9540fd5d6876ed6', 'd6d920eb201e88e2',
            ],
            'reason': (
                "a solver stopped at a duality gap g is within g of the optimum: SLSQP's below "
                "1e-5 (about 1e-14 here), SMO's n C tol = 3e-7 at tol=1e-8"
            ),
        },
    },
    'ex07_backprop': {
        'loss': {
            'kind': 'rel', 'width': 1e-09,
            'salt': 'ex07_backprop/loss',
            'kdf': {'name': 'scrypt', 'n': 2048, 'r': 8, 'p': 1},
            'cells': [
                '51c56ecf95d5ec08', '5380f96eb8277330', '64adcf36aa8a4de1', '6b3bd6ba5d132309',
                '7735ff0b087b374f', '8c137b9b7b6714cc', '98a23220958e51bf', '9a053ef950eea566',
                'a3616298fce5fd27', 'd21a210ae5f50d3d', 'd2749562b51a8c60',
            ],
            'reason': (
                'the same formula summed in another order changes only the last few of 16 digits'
            ),
        },
        'loss_after_step': {
            'kind': 'rel', 'width': 1e-09,
            'salt': 'ex07_backprop/loss_after_step',
            'kdf': {'name': 'scrypt', 'n': 2048, 'r': 8, 'p': 1},
            'cells': [
                '0390ba6d1e837a41', '28f78724c35931c4', '5dfc81d86c74e556', '62ea47d70b9b31da',
                '77f5d29b41b3f0a7', '7f5494ae5cce8341', '96fec1ecc1cae897', '971d404d51d4fc49',
                '97ce71ab2aac4978', 'b4e7f22755d417a4', 'fe07808bb391a0c3',
            ],
            'reason': (
                'the same formula summed in another order changes only the last few of 16 digits'
            ),
        },
    },
    'ex08_filter_order': {
        'order': {
            'kind': 'abs', 'width': 0.0,
            'salt': 'ex08_filter_order/order',
            'kdf': {'name': 'scrypt', 'n': 2048, 'r': 8, 'p': 1},
            'cells': [
                '65b081a64773147a',
            ],
            'reason': (
                "an integer: the next one above the formula's value"
            ),
        },
        'selectivity': {
            'kind': 'rel', 'width': 1e-06,
            'salt': 'ex08_filter_order/selectivity',
            'kdf': {'name': 'scrypt', 'n': 2048, 'r': 8, 'p': 1},
            'cells': [
                '0131d38d96d354d8', '01e78c8d0fe12965', '0f29bb8398323a82', '3d317179e139bd4a',
                '81cf878cea0ffe18', '8796ef3b85cf2a2c', '8d981d572d7eeaae', '99ff408948c50e5d',
                '9d49577b451c0d9a', 'bf3ce1a047b41b1f', 'f28dbf36adbed6c6',
            ],
            'reason': (
                "the same closed formula; the edges' pre-warping is exact"
            ),
        },
        'radius_sos': {
            'kind': 'rel', 'width': 1e-06,
            'salt': 'ex08_filter_order/radius_sos',
            'kdf': {'name': 'scrypt', 'n': 2048, 'r': 8, 'p': 1},
            'cells': [
                '15eba24ed8219e63', '340a956cdcd0bc17', '4277975bea650219', '54f0b369c228949e',
                '5566e4b78f4d0b56', '590c98411c8505bb', '6e0b4b85bb5683c2', '93711e9f56ee1d44',
                '9b1958286fbe020b', 'a19eeaddcad4cd70', 'b51afb7c1a336d46',
            ],
            'reason': (
                'roots of quadratics from the same design, to rounding'
            ),
        },
        'n_coefficients_ba': {
            'kind': 'abs', 'width': 0.0,
            'salt': 'ex08_filter_order/n_coefficients_ba',
            'kdf': {'name': 'scrypt', 'n': 2048, 'r': 8, 'p': 1},
            'cells': [
                '7e31fd67a02f5637',
            ],
            'reason': (
                'a count of coefficients, which no rounding moves'
            ),
        },
    },
    'ex09_mesh_budget': {
        'n_predicted': {
            'kind': 'abs', 'width': 0.0,
            'salt': 'ex09_mesh_budget/n_predicted',
            'kdf': {'name': 'scrypt', 'n': 2048, 'r': 8, 'p': 1},
            'cells': [
                '2a4a7c98187d60ba',
            ],
            'reason': (
                'a count: rounded up or to the nearest, from the observed order or exactly 4, it '
                'is the same count'
            ),
        },
        'n_needed': {
            'kind': 'abs', 'width': 0.0,
            'salt': 'ex09_mesh_budget/n_needed',
            'kdf': {'name': 'scrypt', 'n': 2048, 'r': 8, 'p': 1},
            'cells': [
                '36175b821e8b2875',
            ],
            'reason': (
                'a count: the smallest mesh that meets the budget'
            ),
        },
        'error_needed': {
            'kind': 'rel', 'width': 0.01,
            'salt': 'ex09_mesh_budget/error_needed',
            'kdf': {'name': 'scrypt', 'n': 2048, 'r': 8, 'p': 1},
            'cells': [
                '27a6691749877884', '3c177b79459826ce', '5f5f06c61699a6fa', '946fe5b7ef7d16b2',
                'aab496f5953d1806', 'c1ef4072fbcb25ee', 'cbfa558fca5d53ad', 'ceaafc834d473fb6',
                'd2a9332b248a4c24', 'e7bdcdcab5f90574', 'f4352288dba64b89',
            ],
            'reason': (
                'an exact frequency from an own root-finder (tolerance 1e-12 or finer) moves this'
                ' error of 1e-4 by far less than 1 %'
            ),
        },
    },
    'ex10_fifo': {
        'samples_after_50ms': {
            'kind': 'abs', 'width': 1.0,
            'salt': 'ex10_fifo/samples_after_50ms',
            'kdf': {'name': 'scrypt', 'n': 2048, 'r': 8, 'p': 1},
            'cells': [
                '2a19f72ce907203d', '3d3e2f1b6189da6c', '541eeadaf823157d', '542c1ceba417e986',
                '8be03bd6c91473e8', '9812d127084e0fbd', '98a9e1273290e2ab', '9ae2db6b0477d698',
                'e7fdc42934273b23', 'ef886c63641cdcb5', 'f09bc8de6949d6cd',
            ],
            'reason': (
                'one sample more or less, as the wait starts between two samples'
            ),
        },
        'arrived_while_reading': {
            'kind': 'abs', 'width': 2.0,
            'salt': 'ex10_fifo/arrived_while_reading',
            'kdf': {'name': 'scrypt', 'n': 2048, 'r': 8, 'p': 1},
            'cells': [
                '025a0e8b2a0479c5', '175c74a3f1097c08', '40324b7520fb7bb0', '527afd715cd4bbc6',
                '55e5851e2da73f5d', '8abb13ae2f5468f2', '914e2ecfc513d747', 'baee21ccdc3babb0',
                'f660818aab1e1c66', 'fb268c9c4b7a5ca0', 'fc25336010125b58',
            ],
            'reason': (
                'an extra register read or two (0.44 ms each) on the virtual clock move it by a '
                'sample or two'
            ),
        },
        'overflow_count': {
            'kind': 'abs', 'width': 0.0,
            'salt': 'ex10_fifo/overflow_count',
            'kdf': {'name': 'scrypt', 'n': 2048, 'r': 8, 'p': 1},
            'cells': [
                'ddc65111fdff72b7',
            ],
            'reason': (
                'a count of bytes, which no rounding moves'
            ),
        },
        'lost': {
            'kind': 'abs', 'width': 1.0,
            'salt': 'ex10_fifo/lost',
            'kdf': {'name': 'scrypt', 'n': 2048, 'r': 8, 'p': 1},
            'cells': [
                '1e17c874a2b27144', '31cc1e9b62896216', '5731e0710d0f9d3b', '5864ad0c88d7f115',
                '645b6debd0f5171d', '6750ffdd848868e7', '76eeb9a72cfc4485', '9262bef391fe1c44',
                '9661c965c56b5c94', '98c167b4bcd09a1f', 'd4242c6b740f1674',
            ],
            'reason': (
                'an extra register read or two (0.44 ms each) on the virtual clock between the '
                "driver's calls move it by one sample"
            ),
        },
        'gap_ms': {
            'kind': 'abs', 'width': 1.0,
            'salt': 'ex10_fifo/gap_ms',
            'kdf': {'name': 'scrypt', 'n': 2048, 'r': 8, 'p': 1},
            'cells': [
                '53d3d98d026503a2', '6f99a61d16c8921b', '70e5b6df74464a91', '7ab7de6e04876886',
                '8e2f39f096e1f92b', '998c803e638ed6fd', 'aa6a2e18b8676ac6', 'e63b5e11a3c3d758',
                'e6b1d29a97787780', 'f65a808fe1048115', 'fc18bec39a1a7cda',
            ],
            'reason': (
                'an extra register read or two (0.44 ms each) on the virtual clock between the '
                "driver's calls move it by under 1 ms"
            ),
        },
        'period_us': {
            'kind': 'rel', 'width': 1e-09,
            'salt': 'ex10_fifo/period_us',
            'kdf': {'name': 'scrypt', 'n': 2048, 'r': 8, 'p': 1},
            'cells': [
                '0a5bcf1d67a6f6ed', '0e7f4ffce3f6b432', '1d810854a39e3bb3', '3cc2539133553b4c',
                '3e96d613d6370a13', '406ffc03372b68c6', '8e8d6a841d1d12e8', '9f6f2ca7281c995c',
                'a7011c1a864f7cb1', 'bd6dc1e8e71f0409', 'cc96ea83c0b96141',
            ],
            'reason': (
                'the middle of the bracket of a 5 % rate tolerance: rounding only'
            ),
        },
    },
    'ex11_rbf_cancellation': {
        'true': {
            'kind': 'rel', 'width': 1e-12,
            'salt': 'ex11_rbf_cancellation/true',
            'kdf': {'name': 'scrypt', 'n': 2048, 'r': 8, 'p': 1},
            'cells': [
                '0bae75274ae5af34', '231bcc919d2f5a32', '56ca32aa94094a13', '6b25c849653ca35f',
                '80185c60b7ae4bac', '81ad18981966979f', 'a2ed6c6a571b7686', 'a9d461dd4b31a33d',
                'db544c03c13311fd', 'db92624b4c0950fa', 'f6d96becdda86234',
            ],
            'reason': (
                'a sum of five squares: only the last digits depend on the order'
            ),
        },
        'bound_1e6': {
            'kind': 'rel', 'width': 1e-06,
            'salt': 'ex11_rbf_cancellation/bound_1e6',
            'kdf': {'name': 'scrypt', 'n': 2048, 'r': 8, 'p': 1},
            'cells': [
                '1bf31c9290d49f56', '2aeb0a5314b4e8c5', '475b7c4d5f3ce58d', '61da774974140968',
                '8b3ca663a8b8d0b5', '950a48f78a2f33ae', 'b33c06c427933017', 'c737a49f0e0d4f58',
                'c9895e72c1f133b2', 'd330dfbc5dd5e553', 'd77bc8bd524a398a',
            ],
            'reason': (
                'the formula of the hint; norms summed in any order'
            ),
        },
        'error_1e6': {
            'kind': 'factor', 'width': 10.0,
            'salt': 'ex11_rbf_cancellation/error_1e6',
            'kdf': {'name': 'scrypt', 'n': 2048, 'r': 8, 'p': 1},
            'cells': [
                '1b22442237f30621', '1fc22b5efad9fae4', '3d233a4ad10211d1', '603b276a9192ad2a',
                '6757f2b7a482c5de', '9a55154c6a125f0c', 'af8dc4dbb9e5d205', 'b2859f8a8428ec54',
                'ddb0889697b0a8b6', 'e6daf9d9235b16cc', 'e9b40d34dd7354e2',
            ],
            'reason': (
                'rounding errors depend on the order of the operations: sums in another order '
                'differ by a factor of up to 6'
            ),
        },
        'error_1e6_sums': {
            'kind': 'factor', 'width': 10.0,
            'salt': 'ex11_rbf_cancellation/error_1e6_sums',
            'kdf': {'name': 'scrypt', 'n': 2048, 'r': 8, 'p': 1},
            'cells': [
                '1b9c69aa71937aed', '221cc2fca40c9623', '4f7ddfc4933e9457', '55848f0d53a7f8f5',
                '6b6578ebc8210db7', '784c493a0ac5b6f1', '845659f93b6c03d4', '999be71e6bc29150',
                'ccf1463df61deaa6', 'ce9230436ee33294', 'e40e7aab8cf14b6c',
            ],
            'reason': (
                'rounding errors depend on the order of the operations: sums in another order '
                'differ by a factor of up to 6'
            ),
        },
        'direct_error_1e6': {
            'kind': 'factor', 'width': 10.0,
            'salt': 'ex11_rbf_cancellation/direct_error_1e6',
            'kdf': {'name': 'scrypt', 'n': 2048, 'r': 8, 'p': 1},
            'cells': [
                '03fb231745ea6e72', '2646052f3148ea56', '363b462de16996e5', '41d361a422939b70',
                '65f7c51dd5d12f83', '9089a0e3654f018f', 'b19b7703afc3b291', 'b9b0d884b2713996',
                'c62827d6ed062089', 'e11ec498e4fc4d7e', 'f5937a805c50a7b0',
            ],
            'reason': (
                'rounding errors depend on the order of the operations: sums in another order '
                'differ by a factor of up to 6'
            ),
        },
        'libsvm_drift_1e6': {
            'kind': 'factor', 'width': 3.0,
            'salt': 'ex11_rbf_cancellation/libsvm_drift_1e6',
            'kdf': {'name': 'scrypt', 'n': 2048, 'r': 8, 'p': 1},
            'cells': [
                '19fc56bb2643d377', '27e82c8a0fae7582', '30c06ca2618c3fbc', '34fccb9d3fa7bf8e',
                '559fa6d3bd3253e5', '70de46075fe92238', 'a70a9be697855db9', 'bf341e001c108511',
                'cfe6dd15f8fff883', 'e127f07c6131e55d', 'e847da2b2cbac6b2',
            ],
            'reason': (
                'scikit-learn versions and BLAS libraries round the training kernel differently'
            ),
        },
    },
    'ex12_splits': {
        'chance': {
            'kind': 'abs', 'width': 0.005,
            'salt': 'ex12_splits/chance',
            'kdf': {'name': 'scrypt', 'n': 2048, 'r': 8, 'p': 1},
            'cells': [
                '15944aac734abc31', '53a93dcbcafe53f1', '568aa8a2516c8e38', '56c063db84190bcf',
                '7824ecd31928e2a0', '9d0dc57818e841bc', 'a195b82cc3d874a4', 'c24543fb09d950dd',
                'cae534993af6839b', 'cdd1ff0b3bbba9cc', 'd4e2c69b034efc00',
            ],
            'reason': (
                'one over the number of materials, rounded to two digits'
            ),
        },
        'seen_random': {
            'kind': 'abs', 'width': 0.0,
            'salt': 'ex12_splits/seen_random',
            'kdf': {'name': 'scrypt', 'n': 2048, 'r': 8, 'p': 1},
            'cells': [
                'cb8b40a95c2e1d65',
            ],
            'reason': (
                'a share of whole recordings, from the seeded split'
            ),
        },
        'seen_grouped': {
            'kind': 'abs', 'width': 0.0,
            'salt': 'ex12_splits/seen_grouped',
            'kdf': {'name': 'scrypt', 'n': 2048, 'r': 8, 'p': 1},
            'cells': [
                '03e77d0e356795b7',
            ],
            'reason': (
                'a share of whole recordings, from the seeded split'
            ),
        },
        'accuracy_random': {
            'kind': 'abs', 'width': 0.035,
            'salt': 'ex12_splits/accuracy_random',
            'kdf': {'name': 'scrypt', 'n': 2048, 'r': 8, 'p': 1},
            'cells': [
                '059dfb4f4add63f9', '2570f961cc36daa8', '2d330d35fa06e63f', '4969f3d99abed13c',
                '87bfd1282ebb2c09', 'affd009ed545fb26', 'bf52fb8d0a0c0f18', 'd25cd02fe8ec52ce',
                'd491b3c89644ef2e', 'deda40caa037dd11', 'e8a6fbff637abe55',
            ],
            'reason': (
                'the same data and split; another solver tolerance may flip one test recording of'
                ' 30'
            ),
        },
        'accuracy_grouped': {
            'kind': 'abs', 'width': 0.035,
            'salt': 'ex12_splits/accuracy_grouped',
            'kdf': {'name': 'scrypt', 'n': 2048, 'r': 8, 'p': 1},
            'cells': [
                '010232f151bc267d', '02fab846f44c6363', '11101da876cca471', '3e81e07249bd8d9c',
                '3ed9769a66f35b87', '454372bce695e7fc', '459cf16ff30a6078', '9b9ad231dbe7a721',
                'afe6c4bdc32f668e', 'f6f0a0aa846bb2df', 'fff806b47e3bd2b8',
            ],
            'reason': (
                'the same data and split; another solver tolerance may flip one test recording of'
                ' 30'
            ),
        },
        'accuracy_rigid': {
            'kind': 'abs', 'width': 0.035,
            'salt': 'ex12_splits/accuracy_rigid',
            'kdf': {'name': 'scrypt', 'n': 2048, 'r': 8, 'p': 1},
            'cells': [
                '13b100cd571ea33c', '16a1af549311eeca', '4e10bd7b4f7bb5d4', '8e7d8d1bb1c927ba',
                '967eb63f42f92150', 'c2614744d76b309f', 'c7f64f7e544488d9', 'ce05f37a572cc335',
                'f3af5b31963c334a', 'f482da673e418a86', 'f4e03bbd0774bc75',
            ],
            'reason': (
                'the same data and split; another solver tolerance may flip one test recording of'
                ' 30'
            ),
        },
    },
    'ex13_mode_curves': {
        'spread_f1_pct': {
            'kind': 'rel', 'width': 0.1,
            'salt': 'ex13_mode_curves/spread_f1_pct',
            'kdf': {'name': 'scrypt', 'n': 2048, 'r': 8, 'p': 1},
            'cells': [
                '0b56e5a656c6082d', '1c5c9afd3dc6186d', '3ca92c711335da25', '6f82b51e91a2d724',
                '70be9aea56daec1c', '790ca12b59e5c73e', 'ab62d9499b17d70e', 'c7ea8ff7446f7d25',
                'f13f4c1cf09cb859', 'faece858732aa54a', 'ff97d18a5144d385',
            ],
            'reason': (
                'peak_frequencies interpolates between FFT bins: another interpolation moves a '
                'peak by a small part of a bin'
            ),
        },
        'spread_f2_pct': {
            'kind': 'rel', 'width': 0.1,
            'salt': 'ex13_mode_curves/spread_f2_pct',
            'kdf': {'name': 'scrypt', 'n': 2048, 'r': 8, 'p': 1},
            'cells': [
                '068e900b892e9677', '11a9424798e852ee', '557276d8a98f6340', '64cfd33fd1395f89',
                '8d804d01b0ed18c0', '9dc7814aff3d722e', 'a8db2e97ea52f872', 'b3138d5ee517d3d2',
                'b61ad1cfcb5511ff', 'cb35888ac35a2954', 'dba9d392c7395ffe',
            ],
            'reason': (
                'peak_frequencies interpolates between FFT bins: another interpolation moves a '
                'peak by a small part of a bin'
            ),
        },
        'repeat_pct': {
            'kind': 'rel', 'width': 0.1,
            'salt': 'ex13_mode_curves/repeat_pct',
            'kdf': {'name': 'scrypt', 'n': 2048, 'r': 8, 'p': 1},
            'cells': [
                '0a7d6ab381b9881b', '25321eea3c0049b2', '3bea40129a1951e0', '3fa03992a8a71fac',
                '5a4afc0e942f945c', '667475b1f9aa3198', '674f7db6b62e6bef', '7540ebf6bee65a38',
                '923d5811d51f1492', 'f891b93c359de549', 'fc1beb72d7091eac',
            ],
            'reason': (
                'peak_frequencies interpolates between FFT bins: another interpolation moves a '
                'peak by a small part of a bin'
            ),
        },
        'curve_accuracy': {
            'kind': 'abs', 'width': 0.03,
            'salt': 'ex13_mode_curves/curve_accuracy',
            'kdf': {'name': 'scrypt', 'n': 2048, 'r': 8, 'p': 1},
            'cells': [
                '0eed5694f2c9946c', '2177def426474c85', '29dab449972edf1d', '2b705221648f049c',
                '302e01e2c29af54e', '4b61d31a6a06c188', '7ac9cdd6df818fdd', '95b71de7118ba405',
                '9aa40c28db08d093', 'b136901840a42176', 'd927eb3923e94d9d',
            ],
            'reason': (
                'the same data and split; another solver tolerance may flip a recording or two of'
                ' the held-out set'
            ),
        },
        'n_correct': {
            'kind': 'abs', 'width': 2.0,
            'salt': 'ex13_mode_curves/n_correct',
            'kdf': {'name': 'scrypt', 'n': 2048, 'r': 8, 'p': 1},
            'cells': [
                '1e9952c2b4cc7ebb', '35924f2b28b0a1dc', '3cdb1c3c427250d7', '5bc147a20d86f0b5',
                '6a8402d83f9bd38a', '707a67f53c6b81fa', '8a3a5400b1f41b3e', '9541de60c67550b6',
                'a24f94de8f673fa5', 'a260e5b403012a51', 'dc42d45bf63a5625',
            ],
            'reason': (
                'the same data and split; another solver tolerance may flip a recording or two of'
                ' the held-out set'
            ),
        },
        'n_test': {
            'kind': 'abs', 'width': 0.0,
            'salt': 'ex13_mode_curves/n_test',
            'kdf': {'name': 'scrypt', 'n': 2048, 'r': 8, 'p': 1},
            'cells': [
                'b87748eb9181ce77',
            ],
            'reason': (
                'the held-out recordings of the seeded grouped split'
            ),
        },
        'distance_cm': {
            'kind': 'rel', 'width': 0.1,
            'salt': 'ex13_mode_curves/distance_cm',
            'kdf': {'name': 'scrypt', 'n': 2048, 'r': 8, 'p': 1},
            'cells': [
                '0ef0e29391c78bd0', '1ddccc0b2b7ad86e', '29b935cced83f44c', '42a40aac9a842359',
                '69ab12311e96ad3e', '77af94a472795f31', '907dfa7acbbe0c5f', '9a1d5c72246fd44f',
                'b7884123ead58688', 'bf4d05820b36f9fb', 'e6b3d00045e9ef85',
            ],
            'reason': (
                'peak_frequencies interpolates between FFT bins: another interpolation moves a '
                'peak by a small part of a bin'
            ),
        },
        'svm_accuracy': {
            'kind': 'abs', 'width': 0.03,
            'salt': 'ex13_mode_curves/svm_accuracy',
            'kdf': {'name': 'scrypt', 'n': 2048, 'r': 8, 'p': 1},
            'cells': [
                '07f485e3b175e81b', '157911f9bbf92a16', '37e9fa0a6d841c46', '4fbb3459e6cc20b0',
                '54d719026e6f548d', '90555af43d93cccd', '9eb92c1a90a47514', 'b54078fa9c46bd66',
                'c45a8971959d3c6e', 'd29fd24ad891f1c4', 'da681c4c40e3c8cf',
            ],
            'reason': (
                'the same data and split; another solver tolerance may flip a recording or two of'
                ' the held-out set'
            ),
        },
        'bins_per_cm': {
            'kind': 'rel', 'width': 0.1,
            'salt': 'ex13_mode_curves/bins_per_cm',
            'kdf': {'name': 'scrypt', 'n': 2048, 'r': 8, 'p': 1},
            'cells': [
                '60d40c9f180ef51d', 'a9970ba0d6e2c637', 'd5eb444e2a63c047', 'd7c0293032710e88',
                'e9b7a18fa566451f', 'ea122de827277a53', 'ed43088c943e9bed', 'f1aa8f728d3a34c3',
                'f7703bba592988d9', 'f85494aa617b61ff', 'fac48de39a14f482',
            ],
            'reason': (
                'a jump threshold of 5 to 20 bins, or another peak interpolation, moves the '
                'median by a few per cent'
            ),
        },
        'metals_smooth_from_cm': {
            'kind': 'abs', 'width': 1.0,
            'salt': 'ex13_mode_curves/metals_smooth_from_cm',
            'kdf': {'name': 'scrypt', 'n': 2048, 'r': 8, 'p': 1},
            'cells': [
                '3bc81811521ccd3b', '3de298c289c7f596', '4e33b32105a2e2f7', '542c122bc1d23fb7',
                '55e637130132c463', '56f51a654430d0f5', '75674e0d4b15f1ba', '872d42261a6219b6',
                'ae8e2c9e214b4a29', 'c93394418664da06', 'd705384afc694b9a',
            ],
            'reason': (
                'one 1 cm step: a jump threshold other than 10 bins may move an end by a position'
            ),
        },
        'metals_smooth_to_cm': {
            'kind': 'abs', 'width': 1.0,
            'salt': 'ex13_mode_curves/metals_smooth_to_cm',
            'kdf': {'name': 'scrypt', 'n': 2048, 'r': 8, 'p': 1},
            'cells': [
                '2810729e9589ff5c', '2a9835ddf85c164e', '2fee035f13fd3927', '48fdb9bb0ebe726e',
                '4e71de0c3b97aa91', '5d68aed94841772d', '61c3c74d25ab277b', '7d6f9570d966ed96',
                '7f7bdb530d49fe1c', 'b1ff20edc52a3a0b', 'df42b1910807ec12',
            ],
            'reason': (
                'one 1 cm step: a jump threshold other than 10 bins may move an end by a position'
            ),
        },
        'pvc_smooth_from_cm': {
            'kind': 'abs', 'width': 1.0,
            'salt': 'ex13_mode_curves/pvc_smooth_from_cm',
            'kdf': {'name': 'scrypt', 'n': 2048, 'r': 8, 'p': 1},
            'cells': [
                '004661d869e90fb7', '295ffc3a4f208add', '414cf48cdde17eb7', '547a72f364a45a0c',
                '705890b865641cb4', '746b757854347435', '8a16a149cbc6da81', '8afe57794d5e5768',
                'c83ae3e86e40107f', 'da1c5233dc9e0d0f', 'dc8b71f283e2e681',
            ],
            'reason': (
                'one 1 cm step: a jump threshold other than 10 bins may move an end by a position'
            ),
        },
        'pvc_smooth_to_cm': {
            'kind': 'abs', 'width': 1.0,
            'salt': 'ex13_mode_curves/pvc_smooth_to_cm',
            'kdf': {'name': 'scrypt', 'n': 2048, 'r': 8, 'p': 1},
            'cells': [
                '06177fcc34d0e270', '1be877267e89353a', '4534dbd4af788f11', '6603685009f0875b',
                '73a245a17f3664f5', '75c39466ffc3d5f1', '80dba6d850a1d322', 'bafa6936ae78928d',
                'be4169abdcf1afe8', 'c1f4d0eccaf163af', 'e6b954b809578f16',
            ],
            'reason': (
                'one 1 cm step: a jump threshold other than 10 bins may move an end by a position'
            ),
        },
        'restrikes_median': {
            'kind': 'abs', 'width': 1.0,
            'salt': 'ex13_mode_curves/restrikes_median',
            'kdf': {'name': 'scrypt', 'n': 2048, 'r': 8, 'p': 1},
            'cells': [
                '40732fbea7a1c767', '60d30fde8e87b5ab', '61021c08e7441892', '7052ec44c3696fbe',
                '8e66ef30d198cb95', '989473df77d4c891', 'a564333981dc0165', 'adf53b003e3672a0',
                'c9e4f80df58216af', 'da5ff4293a4a800a', 'e1988cb86936a423',
            ],
            'reason': (
                'read from the data set; a last-bit difference of the simulation may move a count'
                ' by one'
            ),
        },
        'restrikes_max': {
            'kind': 'abs', 'width': 1.0,
            'salt': 'ex13_mode_curves/restrikes_max',
            'kdf': {'name': 'scrypt', 'n': 2048, 'r': 8, 'p': 1},
            'cells': [
                '22763cb50d69e005', '658e909326056bef', '68893c56d36487e7', '6b2bfc9b26531f7f',
                '82abe7152b4b0906', '89f82635b59f2f7c', '9082a217b042e318', '9bd43eeb4644ec5c',
                'b71656f128e503f6', 'ba2ee99c9c42e541', 'fb10354ec8fd5905',
            ],
            'reason': (
                'read from the data set; a last-bit difference of the simulation may move a count'
                ' by one'
            ),
        },
    },
    'ex14_kalman': {
        'k_steady': {
            'kind': 'rel', 'width': 0.0001,
            'salt': 'ex14_kalman/k_steady',
            'kdf': {'name': 'scrypt', 'n': 2048, 'r': 8, 'p': 1},
            'cells': [
                '0e60ba7c909dd6b7', '1bdd82dc53d006dd', '396cd31d33e768cf', '59f5249860aa6e10',
                '6c12626762072f4e', '80a6c75ef21fce60', '894edbca691bb1a6', '91d1dd64f3c65656',
                '9905d8f26a135d7b', 'b77c69ab6d88cd9f', 'c57ce4d537442a9d',
            ],
            'reason': (
                'a closed form: any right algebra gives it to rounding, or to five copied digits'
            ),
        },
        'sigma_steady': {
            'kind': 'rel', 'width': 0.0001,
            'salt': 'ex14_kalman/sigma_steady',
            'kdf': {'name': 'scrypt', 'n': 2048, 'r': 8, 'p': 1},
            'cells': [
                '252fad2b0ec707ec', '3e103a2a87823904', '47b0c807846b8890', '5314679b3e4fee41',
                '6979f576c5c88f0c', '6fb4ad405ca966cf', '8caf2040c44237d6', '8dc3133503694ed7',
                'ae85216f5acca3c4', 'c06dece7cebe28a8', 'd5677dbd6cb4e805',
            ],
            'reason': (
                'a closed form: any right algebra gives it to rounding, or to five copied digits'
            ),
        },
        'rms_raw': {
            'kind': 'rel', 'width': 0.001,
            'salt': 'ex14_kalman/rms_raw',
            'kdf': {'name': 'scrypt', 'n': 2048, 'r': 8, 'p': 1},
            'cells': [
                '081ec8200c26f418', '0b6d388ab663036e', '219f251722194609', '2aa7b5b5e2768ce4',
                '3315c828deb59db7', '5705d6668fcae087', '7866531585668d15', '85dcb58cb2fa3308',
                '8fcbb6cb98993483', 'a1a999ea87b81f63', 'bffa81386d9b9d63',
            ],
            'reason': (
                'the statement fixes the data, the filter and the cut at 1000 samples: only sums '
                'differ'
            ),
        },
        'rms_filtered': {
            'kind': 'rel', 'width': 0.001,
            'salt': 'ex14_kalman/rms_filtered',
            'kdf': {'name': 'scrypt', 'n': 2048, 'r': 8, 'p': 1},
            'cells': [
                '0e85fb33d610c719', '122f7ee77fa3d45d', '4421cc5aebe0febf', '4999231b35ebe63e',
                '6aa3b6e2653c748e', 'b5b1e6e0a778288d', 'da1148ee12950aa8', 'dae62760df16aa55',
                'dcf06f5a2f0a0c32', 'e761b62d56552156', 'ee48cdcf827ffa1a',
            ],
            'reason': (
                'the statement fixes the data, the filter and the cut at 1000 samples: only sums '
                'differ'
            ),
        },
        'rms_q_small': {
            'kind': 'rel', 'width': 0.001,
            'salt': 'ex14_kalman/rms_q_small',
            'kdf': {'name': 'scrypt', 'n': 2048, 'r': 8, 'p': 1},
            'cells': [
                '26b63c763a4a4be5', '44ef1315f227ee27', '540da787bb456860', '7724e29418b0c0b7',
                '918d5cb68fa30160', 'b15f9624491347f5', 'bfbfa43ea06397ee', 'c20512c4e5fc5b73',
                'cc34a538c94e5953', 'ea9b29d0f8ee97ad', 'f1ecec291fd93b07',
            ],
            'reason': (
                'the statement fixes the data, the filter and the cut at 1000 samples: only sums '
                'differ'
            ),
        },
        'rms_q_large': {
            'kind': 'rel', 'width': 0.001,
            'salt': 'ex14_kalman/rms_q_large',
            'kdf': {'name': 'scrypt', 'n': 2048, 'r': 8, 'p': 1},
            'cells': [
                '0401aa267fd91740', '114c304e91acb0ce', '1b02037c647193ac', '357416b458b1aa22',
                '562783623bb7b1df', '6122a974d334c051', '753388136fc25e60', 'b407bfbce53c4195',
                'c4bfbf32319422d5', 'e626da5cf8a5ebf6', 'fb446035e7ae0a61',
            ],
            'reason': (
                'the statement fixes the data, the filter and the cut at 1000 samples: only sums '
                'differ'
            ),
        },
    },
    'ex15_design_effect': {
        'accuracy': {
            'kind': 'abs', 'width': 0.0025,
            'salt': 'ex15_design_effect/accuracy',
            'kdf': {'name': 'scrypt', 'n': 2048, 'r': 8, 'p': 1},
            'cells': [
                '0bb65b34781a3ced', '20a2c9fae9f7a496', '25e1341859a7c023', '31c086b29a2361ad',
                '7e89efc782f5dbcc', '93ad37fd8fce6a8d', 'b5015ce14156f32a', 'caa48b970d8b8d45',
                'f1255c105929361c', 'f47361d5b24a80eb', 'f75653bf11fead84',
            ],
            'reason': (
                'a count of right answers out of 200: half of one in 200'
            ),
        },
        'rec_low': {
            'kind': 'rel', 'width': 0.0001,
            'salt': 'ex15_design_effect/rec_low',
            'kdf': {'name': 'scrypt', 'n': 2048, 'r': 8, 'p': 1},
            'cells': [
                '0b532b73596e8b27', '0c1bfaaa2146ce0f', '1bb694aab4ba3401', '35dda3e5ce23faad',
                '482d12e6e51d59d0', '5b5a50a02e0a06bc', '649a8cba6418650d', '7d97a6c55a4cc62d',
                '95dbde2fcd86dafd', 'afdd8a4ac2b8d448', 'd8126cf6be1642d3',
            ],
            'reason': (
                'a closed form of the stated data: rounding, z = 1.96 for 1.95996, or five copied'
                ' digits'
            ),
        },
        'rec_high': {
            'kind': 'rel', 'width': 0.0001,
            'salt': 'ex15_design_effect/rec_high',
            'kdf': {'name': 'scrypt', 'n': 2048, 'r': 8, 'p': 1},
            'cells': [
                '0298783de091d9a0', '0dbf787e281942b5', '11c2493cbfd54cac', '1223fc7d44cadca2',
                '2e5dfa9c55ebae79', '6e2c6cfcbeef9301', '8f426e379db0d749', 'c161af94544d1edd',
                'e77238c38272d26a', 'f8034a20db224f0a', 'fc6f60aa014736e8',
            ],
            'reason': (
                'a closed form of the stated data: rounding, z = 1.96 for 1.95996, or five copied'
                ' digits'
            ),
        },
        'icc': {
            'kind': 'rel', 'width': 0.0001,
            'salt': 'ex15_design_effect/icc',
            'kdf': {'name': 'scrypt', 'n': 2048, 'r': 8, 'p': 1},
            'cells': [
                '0047266a1193fc87', '2048f62d55603422', '2a8749a9206c5257', '603ec00a08f58e51',
                '716fadf957de1080', '96e020020ffdd231', '998eefb7956090bb', 'a561ffe8f6671401',
                'c33d95d0adce9337', 'c9b73f6b1b6f07d8', 'dcd9edea0b783b2e',
            ],
            'reason': (
                'sums of squares of whole counts: rounding only, or five copied digits'
            ),
        },
        'deff_icc': {
            'kind': 'rel', 'width': 0.0001,
            'salt': 'ex15_design_effect/deff_icc',
            'kdf': {'name': 'scrypt', 'n': 2048, 'r': 8, 'p': 1},
            'cells': [
                '0de881b0a3750d66', '1382c016c5dcf8c8', '2f059524055cca31', '42a5c28810424e6a',
                '617aea0d03c5d4f8', '8b6cde103024c346', '94885bc2eccf190d', 'a56b7bef26b75536',
                'b2f7e3941c64e933', 'c71c7e9e9ac967ff', 'f8704efb259bd19d',
            ],
            'reason': (
                'sums of squares of whole counts: rounding only, or five copied digits'
            ),
        },
        'deff': {
            'kind': 'rel', 'width': 0.0001,
            'salt': 'ex15_design_effect/deff',
            'kdf': {'name': 'scrypt', 'n': 2048, 'r': 8, 'p': 1},
            'cells': [
                '025149bb905b1b19', '147e4c77da6e0595', '1abaa7cb50c9f181', '2cdc63885ee4b5d1',
                '6121abaf6fb8838b', '8d0e09bc26431f89', '923aa73dc789c5a1', 'a2b86b666c2d44cd',
                'dd887e1ae538be8c', 'e213e878cc6837a8', 'e700c99a6f329ff5',
            ],
            'reason': (
                'sums of squares of whole counts: rounding only, or five copied digits'
            ),
        },
        'n_eff': {
            'kind': 'rel', 'width': 0.0001,
            'salt': 'ex15_design_effect/n_eff',
            'kdf': {'name': 'scrypt', 'n': 2048, 'r': 8, 'p': 1},
            'cells': [
                '0367263f5b24138a', '262f50cd9cb52c8d', '2a1376551994f936', '3507b1f005bbb761',
                '66be3ad9cffbfccb', '7f1768628ec9b1c7', '805d47f0d1aa5667', '87ef832766c7303c',
                '889d691181196efe', '89f858a0f233ebb5', 'e645a0696691a607',
            ],
            'reason': (
                'sums of squares of whole counts: rounding only, or five copied digits'
            ),
        },
        'eff_low': {
            'kind': 'rel', 'width': 0.0001,
            'salt': 'ex15_design_effect/eff_low',
            'kdf': {'name': 'scrypt', 'n': 2048, 'r': 8, 'p': 1},
            'cells': [
                '31acb027387a81ce', '3e1a79016a05796b', '78a45011987dc64a', '8382358b990710f5',
                '940ea9768b04552f', '9b4115c45754a8a1', 'b6eb6e5e24181d7f', 'b792b7c4c60ebb82',
                'c69151b23d712152', 'c71d3078e67dda1d', 'cba8e0751902d263',
            ],
            'reason': (
                'a closed form of the stated data: rounding, z = 1.96 for 1.95996, or five copied'
                ' digits'
            ),
        },
        'eff_high': {
            'kind': 'rel', 'width': 0.0001,
            'salt': 'ex15_design_effect/eff_high',
            'kdf': {'name': 'scrypt', 'n': 2048, 'r': 8, 'p': 1},
            'cells': [
                '0237d44a44de3cb0', '10229a3550ea0b1a', '1468da3897c092a1', '3ff68c6fb77aac5c',
                '5d0e7b26342c5945', '90acca8b8c1115ab', 'c85662960dcd9e1d', 'ca7a7e0aae9b5878',
                'ebab28fd34043b04', 'ec92b7ff841f385d', 'ef0bd9fcb5851fa9',
            ],
            'reason': (
                'a closed form of the stated data: rounding, z = 1.96 for 1.95996, or five copied'
                ' digits'
            ),
        },
        'boot_low': {
            'kind': 'abs', 'width': 0.0125,
            'salt': 'ex15_design_effect/boot_low',
            'kdf': {'name': 'scrypt', 'n': 2048, 'r': 8, 'p': 1},
            'cells': [
                '055925bdfba6a2e3', '10e40374a8786228', '13caa1a6f9ffc9ad', '4219e9756f4ed599',
                '6ee88ca2cf29d3c3', '70342f36bfd7bed1', '8d636c71beae0360', 'be4e1c46535922f6',
                'c4a680044c861d89', 'dcd1d64c51cd4b05', 'f886eb1dfb3a4904',
            ],
            'reason': (
                "another seed's 10000 resamples move an end by at most 2 steps of 1/200 (4 sd of "
                'a percentile), half a step for quantile conventions'
            ),
        },
        'boot_high': {
            'kind': 'abs', 'width': 0.0125,
            'salt': 'ex15_design_effect/boot_high',
            'kdf': {'name': 'scrypt', 'n': 2048, 'r': 8, 'p': 1},
            'cells': [
                '049c92d9ff04ad8d', '2b4a7ac1398c995f', '2cf3fef21437b947', '328e8618770a7623',
                '35f2076234c2f8bd', '681fa91c132a7dcf', '75caf0fa3b6cf5c3', '96ee19e0eb855f37',
                'b19441245820a5fc', 'b7184e9b257a992c', 'dca7746387956db9',
            ],
            'reason': (
                "another seed's 10000 resamples move an end by at most 2 steps of 1/200 (4 sd of "
                'a percentile), half a step for quantile conventions'
            ),
        },
        'coverage_recording': {
            'kind': 'abs', 'width': 0.0005,
            'salt': 'ex15_design_effect/coverage_recording',
            'kdf': {'name': 'scrypt', 'n': 2048, 'r': 8, 'p': 1},
            'cells': [
                '1a2a1da465128a64', '271cd88992c3c8aa', '417f3e4e9672c013', '60d794eb03b9100d',
                '7c363264debc8e8e', '905d5eb05c5259fa', '96786147639cf697', 'aaca4e5ead3b3211',
                'df8a7ae78821cf8f', 'ee02d56359e92649', 'faa7f8b6fe7302bf',
            ],
            'reason': (
                "a share of 1000 designs: no interval's end lies within 1e-4 of 0.8, so rounding "
                'or z = 1.96 flips none; half a design'
            ),
        },
        'coverage_deff': {
            'kind': 'abs', 'width': 0.0005,
            'salt': 'ex15_design_effect/coverage_deff',
            'kdf': {'name': 'scrypt', 'n': 2048, 'r': 8, 'p': 1},
            'cells': [
                '0b9ca322dea41703', '33bf03c55867c823', '37d2de4692c9ad50', '564dc242112c9641',
                '8b2917ba52202cac', '9f6e79f348a207d7', 'b7d6dd49da28a820', 'be0c8663a7fa29b6',
                'c89aa7f3d7b87f92', 'd53398dbd929dd3e', 'fd11bf9a63d277eb',
            ],
            'reason': (
                "a share of 1000 designs: no interval's end lies within 1e-4 of 0.8, so rounding "
                'or z = 1.96 flips none; half a design'
            ),
        },
    },
}
