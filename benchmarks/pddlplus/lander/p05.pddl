(define (problem lander-05)
  (:domain lander)
  (:init
    (flying)
    (= (h) 1011.6) (= (v) -30)
    (= (mass) 1080.75) (= (fuel) 80.75) (= (burn-rate) 5)
    (= (gravity) 3.71) (= (thrust) 10424.9)
    (= (touch-height) 2) (= (safe-speed) 1.5))
  (:goal (and (landed))))
